"""``rclpy.utilities``: the default context, ok/shutdown, ``remove_ros_args``."""

from __future__ import annotations

from launchkit.ros import ok, remove_ros_args, shutdown, try_shutdown
from launchkit.ros.context import Context, default_context


def get_default_context(*, shutting_down: bool = False) -> Context:
    """The process's default context."""
    return default_context


def get_rmw_implementation_identifier() -> str:
    """The middleware: launchkit speaks rmw_zenoh's wire format."""
    return "rmw_zenoh_cpp"


def timeout_sec_to_nsec(timeout_sec: float | None) -> int:
    """A timeout in seconds as rcl's nanoseconds (-1: forever)."""
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(float(timeout_sec) * 1_000_000_000)


__all__ = [
    "get_default_context",
    "get_rmw_implementation_identifier",
    "ok",
    "remove_ros_args",
    "shutdown",
    "timeout_sec_to_nsec",
    "try_shutdown",
]
