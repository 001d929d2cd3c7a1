"""Time, Duration and clocks; a ROS clock follows ``/clock`` when ``use_sim_time`` is true."""

from __future__ import annotations

import enum
import threading
import time
from functools import total_ordering
from typing import Any

_NS = 1_000_000_000


class ClockType(enum.IntEnum):
    """rcl clock types."""

    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3


@total_ordering
class Duration:
    """A signed span of time in nanoseconds."""

    def __init__(self, *, seconds: float = 0, nanoseconds: int = 0) -> None:
        self.nanoseconds = int(seconds * _NS) + int(nanoseconds)

    def __repr__(self) -> str:
        return f"Duration(nanoseconds={self.nanoseconds})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Duration) and self.nanoseconds == other.nanoseconds

    def __lt__(self, other: Duration) -> bool:
        return self.nanoseconds < other.nanoseconds

    def __hash__(self) -> int:
        return hash(self.nanoseconds)

    def to_msg(self) -> Any:
        """As builtin_interfaces/msg/Duration."""
        from launchkit.ros.msgs import get_message

        sec, nanosec = divmod(self.nanoseconds, _NS)
        return get_message("builtin_interfaces/msg/Duration")(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: Any) -> Duration:
        """From builtin_interfaces/msg/Duration."""
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)


@total_ordering
class Time:
    """A point in time of one clock type, in nanoseconds since its epoch."""

    def __init__(
        self,
        *,
        seconds: float = 0,
        nanoseconds: int = 0,
        clock_type: ClockType = ClockType.SYSTEM_TIME,
    ) -> None:
        self.nanoseconds = int(seconds * _NS) + int(nanoseconds)
        self.clock_type = clock_type

    def __repr__(self) -> str:
        return f"Time(nanoseconds={self.nanoseconds}, clock_type={self.clock_type.name})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Time) and (self.nanoseconds, self.clock_type) == (
            other.nanoseconds,
            other.clock_type,
        )

    def __lt__(self, other: Time) -> bool:
        if self.clock_type != other.clock_type:
            raise TypeError("cannot compare times of different clock types")
        return self.nanoseconds < other.nanoseconds

    def __hash__(self) -> int:
        return hash((self.nanoseconds, self.clock_type))

    def __add__(self, other: Duration) -> Time:
        return Time(nanoseconds=self.nanoseconds + other.nanoseconds, clock_type=self.clock_type)

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Time):
            return Duration(nanoseconds=self.nanoseconds - other.nanoseconds)
        return Time(nanoseconds=self.nanoseconds - other.nanoseconds, clock_type=self.clock_type)

    def seconds_nanoseconds(self) -> tuple[int, int]:
        """(whole seconds, remaining nanoseconds)."""
        sec, nanosec = divmod(self.nanoseconds, _NS)
        return sec, nanosec

    def to_msg(self) -> Any:
        """As builtin_interfaces/msg/Time."""
        from launchkit.ros.msgs import get_message

        sec, nanosec = self.seconds_nanoseconds()
        return get_message("builtin_interfaces/msg/Time")(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: Any, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        """From builtin_interfaces/msg/Time."""
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)


class Clock:
    """A clock: ``now()``; a ROS_TIME clock can be switched to sim time (set by ``/clock``)."""

    def __init__(self, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> None:
        self.clock_type = clock_type
        self._sim_ns: int | None = None  # None: sim time off
        self._lock = threading.Lock()

    def now(self) -> Time:
        """The current time of this clock."""
        if self._sim_ns is not None:
            return Time(nanoseconds=self._sim_ns, clock_type=self.clock_type)
        if self.clock_type == ClockType.STEADY_TIME:
            return Time(nanoseconds=time.monotonic_ns(), clock_type=self.clock_type)
        return Time(nanoseconds=time.time_ns(), clock_type=self.clock_type)

    @property
    def ros_time_is_active(self) -> bool:
        """True when this ROS clock follows ``/clock``."""
        return self._sim_ns is not None

    def _set_ros_time_override(self, active: bool) -> None:
        if self.clock_type != ClockType.ROS_TIME:
            raise RuntimeError("only a ROS_TIME clock can follow /clock")
        with self._lock:
            self._sim_ns = 0 if active else None

    def _set_sim_time(self, nanoseconds: int) -> None:
        with self._lock:
            if self._sim_ns is None:
                return
            self._sim_ns = nanoseconds

    def sleep_for(self, duration: Duration) -> None:
        """Sleep for ``duration`` of this clock (steady time when not simulated)."""
        if self._sim_ns is None:
            time.sleep(max(0.0, duration.nanoseconds / _NS))
            return
        target = self._sim_ns + duration.nanoseconds
        while self._sim_ns is not None and self._sim_ns < target:
            time.sleep(0.001)


class ROSClock(Clock):
    """The clock nodes use: system time, or ``/clock`` when ``use_sim_time`` is true."""

    def __init__(self) -> None:
        super().__init__(clock_type=ClockType.ROS_TIME)
