"""``rclpy.exceptions``: rclpy's exceptions."""

from launchkit.ros.exceptions import *  # noqa: F403
from launchkit.ros.exceptions import __all__ as __all__
