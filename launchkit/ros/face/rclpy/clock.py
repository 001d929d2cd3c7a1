"""``rclpy.clock``: clocks, sleeps and time jumps."""

from launchkit.ros.clock import (
    Clock,
    ClockChange,
    ClockType,
    JumpHandle,
    JumpThreshold,
    ROSClock,
    TimeJump,
)

__all__ = [
    "Clock",
    "ClockChange",
    "ClockType",
    "JumpHandle",
    "JumpThreshold",
    "ROSClock",
    "TimeJump",
]
