"""``rclpy.event_handler``: publisher and subscription events (matched)."""

from launchkit.ros.event_handler import *  # noqa: F403
from launchkit.ros.event_handler import __all__ as __all__
