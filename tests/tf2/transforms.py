"""Building TransformStamped messages and reading results, for the tf2 tests."""

from __future__ import annotations

import math
from typing import Any

from launchkit.ros.msgs import get_message

NS = 1_000_000_000


def stamped(
    parent: str,
    child: str,
    sec: int = 0,
    nanosec: int = 0,
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
    q: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0),
) -> Any:
    """A TransformStamped ``parent -> child`` at ``sec.nanosec``."""
    message = get_message("geometry_msgs/msg/TransformStamped")()
    message.header.frame_id, message.child_frame_id = parent, child
    message.header.stamp.sec, message.header.stamp.nanosec = sec, nanosec
    t, r = message.transform.translation, message.transform.rotation
    t.x, t.y, t.z = xyz
    r.x, r.y, r.z, r.w = q
    return message


def yaw(angle: float) -> tuple[float, float, float, float]:
    """The rotation by ``angle`` radians about +z."""
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


def translation(message: Any) -> tuple[float, float, float]:
    """A TransformStamped's translation."""
    t = message.transform.translation
    return (t.x, t.y, t.z)


def rotation(message: Any) -> tuple[float, float, float, float]:
    """A TransformStamped's rotation."""
    r = message.transform.rotation
    return (r.x, r.y, r.z, r.w)


def stamp_ns(message: Any) -> int:
    """A message's header stamp in nanoseconds."""
    return int(message.header.stamp.sec) * NS + int(message.header.stamp.nanosec)
