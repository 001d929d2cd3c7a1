"""``rclpy.qos_event``: rclpy's older name of ``rclpy.event_handler``."""

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
