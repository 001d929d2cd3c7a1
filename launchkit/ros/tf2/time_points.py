"""Times and durations as tf2 takes and prints them: integer nanoseconds inside, and
``%.6f`` seconds in its messages.

A time argument is whatever ``tf2_py`` accepts: a message with ``sec`` and ``nanosec``
(``builtin_interfaces/Time``, a header's stamp) or an object with ``nanoseconds`` (rclpy's
``Time``); its clock type is not looked at. Zero means "the latest time the frames share".
"""

from __future__ import annotations

from typing import Any

NS_PER_SECOND = 1_000_000_000


def time_ns(value: Any) -> int:
    """``value`` (a Time message or an rclpy Time) as nanoseconds since the epoch."""
    return _nanoseconds(value, "time")


def duration_ns(value: Any) -> int:
    """``value`` (a Duration message or an rclpy Duration) as nanoseconds."""
    return _nanoseconds(value, "duration")


def _nanoseconds(value: Any, what: str) -> int:
    if hasattr(value, "sec") and hasattr(value, "nanosec"):
        return int(value.sec) * NS_PER_SECOND + int(value.nanosec)
    if hasattr(value, "nanoseconds"):
        return int(value.nanoseconds)
    raise TypeError(f"{what} must have sec and nanosec, or nanoseconds.")


def to_seconds(ns: int) -> float:
    """Nanoseconds as seconds, whole seconds and the rest scaled apart (tf2's
    ``durationToSec``, which keeps the nanoseconds exact for large times)."""
    whole, rest = divmod(abs(ns), NS_PER_SECOND)
    if ns < 0:
        whole, rest = -whole, -rest
    return float(whole) + 1e-9 * float(rest)


def display(ns: int) -> str:
    """A time as tf2 prints it in its messages: seconds with six decimals."""
    return f"{to_seconds(ns):.6f}"


def sec_nanosec(ns: int) -> tuple[int, int]:
    """``(sec, nanosec)`` of a time, as a Time message holds it."""
    return divmod(ns, NS_PER_SECOND)
