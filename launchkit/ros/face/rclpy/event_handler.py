"""``rclpy.event_handler``: publisher and subscription events (matched)."""

from launchkit.ros.event_handler import (
    PublisherEventCallbacks,
    QoSPublisherMatchedInfo,
    QoSSubscriptionMatchedInfo,
    SubscriptionEventCallbacks,
)

__all__ = [
    "PublisherEventCallbacks",
    "QoSPublisherMatchedInfo",
    "QoSSubscriptionMatchedInfo",
    "SubscriptionEventCallbacks",
]
