"""``rclpy.timer``: timers and rates."""

from launchkit.ros.rate import Rate
from launchkit.ros.timer import Timer

__all__ = ["Rate", "Timer"]
