"""``rclpy.qos_event``: rclpy's older name of ``rclpy.event_handler``."""

from launchkit.ros.event_handler import *  # noqa: F403
from launchkit.ros.event_handler import __all__ as __all__
