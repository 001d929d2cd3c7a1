"""The real rclpy, imported on demand: clear errors where it is missing, type lookup, QoS.

rclpy comes from a ROS 2 Jazzy install (``source /opt/ros/jazzy/setup.bash``) or from the
third-party PyPI wheels the ``ros2`` extra installs (CPython 3.11 on Linux x86_64 only).
"""

from __future__ import annotations

import importlib
import platform
import sys
from types import ModuleType
from typing import Any

from launchkit.errors import UserError
from launchkit.ros.qos import QoSProfile, known_profile

EXTRA = "launchkit[ros2]"
WHEEL_PLATFORM = "CPython 3.11 on Linux x86_64"


class RclpyUnavailableError(UserError):
    """The real rclpy cannot be imported here."""


def wheels_supported() -> bool:
    """Whether the PyPI ros-jazzy wheels exist for this interpreter and machine."""
    return (
        sys.implementation.name == "cpython"
        and sys.version_info[:2] == (3, 11)
        and sys.platform == "linux"
        and platform.machine() == "x86_64"
    )


def import_rclpy() -> ModuleType:
    """``rclpy``, or a one-line error saying how to get it on this machine."""
    try:
        import rclpy
        import rclpy.executors
        import rclpy.serialization  # the bridge needs both: fail here, not later
    except ImportError as exc:
        here = (
            f"{platform.python_implementation()} {platform.python_version()} on "
            f"{platform.system()} {platform.machine()}"
        )
        if wheels_supported():
            how = f"pip install '{EXTRA}'"
        else:
            how = (
                f"source a ROS 2 Jazzy install first (the PyPI wheels of '{EXTRA}' exist only "
                f"for {WHEEL_PLATFORM}; this is {here})"
            )
        raise RclpyUnavailableError(
            f"the ROS 2 bridge needs the real rclpy, which cannot be imported ({exc})",
            expected=f"rclpy importable: {how}",
        ) from None
    return rclpy


#: an action's services and feedback message, as rosidl's action class holds them in ``Impl``
_ACTION_PARTS = {
    "_SendGoal": "SendGoalService",
    "_GetResult": "GetResultService",
    "_FeedbackMessage": "FeedbackMessage",
}


def message_class(type_name: str) -> Any | None:
    """rclpy's class for ``pkg/msg/Name``, ``pkg/srv/Name`` or an action's part
    (``pkg/action/Name_SendGoal``, ``_GetResult``, ``_FeedbackMessage``); None when not
    installed."""
    package, kind, name = type_name.split("/")
    try:
        module = importlib.import_module(f"{package}.{kind}")
    except ImportError:
        return None
    found = getattr(module, name, None)
    if found is not None or kind != "action":
        return found
    for suffix, part in _ACTION_PARTS.items():
        if name.endswith(suffix):
            action = getattr(module, name[: -len(suffix)], None)
            return None if action is None else getattr(action.Impl, part, None)
    return None


def to_rclpy_qos(qos: QoSProfile) -> Any:
    """The rclpy profile for a launchkit one (KEEP_LAST of the effective depth, or KEEP_ALL)."""
    from rclpy.qos import DurabilityPolicy as Durability
    from rclpy.qos import HistoryPolicy as History
    from rclpy.qos import QoSProfile as RclpyQoS
    from rclpy.qos import ReliabilityPolicy as Reliability

    known = known_profile(qos.effective_depth, qos.reliability, qos.durability, qos.history)
    return RclpyQoS(  # type: ignore[no-untyped-call]
        history=History(int(known.history)),
        depth=known.depth,
        reliability=Reliability(int(known.reliability)),
        durability=Durability(int(known.durability)),
    )


def from_rclpy_qos(qos: Any, default_depth: int) -> QoSProfile:
    """A launchkit profile for what DDS discovery reports (Fast DDS reports no depth)."""
    return known_profile(
        int(qos.depth) or default_depth, qos.reliability, qos.durability, qos.history
    )
