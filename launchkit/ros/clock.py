"""Time, Duration and clocks (rclpy's ``rclpy.time``, ``rclpy.duration``, ``rclpy.clock``).

A ROS clock follows ``/clock`` while ROS time is active (a node's ``use_sim_time``): each
message sets the time it reports (``set_ros_time_override``), and jump callbacks hear when
ROS time is switched on or off and when it moves by more than their thresholds.
"""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol

from launchkit.ros.ros_time import ClockType as ClockType
from launchkit.ros.ros_time import Duration as Duration
from launchkit.ros.ros_time import Infinite as Infinite
from launchkit.ros.ros_time import Time as Time

if TYPE_CHECKING:
    from launchkit.ros.context import Context

_NS = 1_000_000_000
_POLL = 0.1  # how often a sleep looks whether its context was shut down (a signal, say)


class ClockChange(enum.IntEnum):
    """What a time jump was."""

    ROS_TIME_NO_CHANGE = 1
    ROS_TIME_ACTIVATED = 2
    ROS_TIME_DEACTIVATED = 3
    SYSTEM_TIME_NO_CHANGE = 4


class JumpThreshold:
    """Which jumps a jump callback hears: forward or backward by at least so much, and ROS
    time switched on or off."""

    def __init__(
        self,
        *,
        min_forward: Duration | None,
        min_backward: Duration | None,
        on_clock_change: bool = True,
    ) -> None:
        if min_forward is not None and min_forward.nanoseconds <= 0:
            raise ValueError("min_forward must be a positive non-zero duration")
        if min_backward is not None and min_backward.nanoseconds >= 0:
            raise ValueError("min_backward must be a negative non-zero duration")
        if min_forward is None and min_backward is None and not on_clock_change:
            raise ValueError("At least one jump threshold must be enabled")
        self.min_forward = min_forward
        self.min_backward = min_backward
        self.on_clock_change = on_clock_change


class TimeJump:
    """A jump of a clock: its kind and how far it went."""

    def __init__(self, clock_change: ClockChange, delta: Duration) -> None:
        self._clock_change = clock_change
        self._delta = delta

    @property
    def clock_change(self) -> ClockChange:
        """What kind of jump."""
        return self._clock_change

    @property
    def delta(self) -> Duration:
        """How far the time moved."""
        return self._delta


class JumpHandle:
    """A registered jump callback; ``unregister()`` (or leaving its ``with``) removes it."""

    def __init__(
        self,
        *,
        clock: Clock,
        threshold: JumpThreshold,
        pre_callback: Callable[[], None] | None,
        post_callback: Callable[[TimeJump], None] | None,
    ) -> None:
        self._clock: Clock | None = clock
        self.threshold = threshold
        self.pre_callback = pre_callback
        self.post_callback = post_callback
        clock._jump_handles.append(self)

    def unregister(self) -> None:
        """Stop calling the callbacks."""
        if self._clock is not None and self in self._clock._jump_handles:
            self._clock._jump_handles.remove(self)
        self._clock = None

    def __enter__(self) -> JumpHandle:
        return self

    def __exit__(self, *_: object) -> None:
        self.unregister()


class Clock:
    """A clock: ``now()``, sleeps, jump callbacks. ``Clock(clock_type=ROS_TIME)`` is a
    :class:`ROSClock`."""

    def __new__(cls, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> Clock:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        if clock_type == ClockType.ROS_TIME and not issubclass(cls, ROSClock):
            return super().__new__(ROSClock)
        return super().__new__(cls)

    def __init__(self, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> None:
        self._clock_type = clock_type
        self._jump_handles: list[JumpHandle] = []
        self._lock = threading.Lock()

    @property
    def clock_type(self) -> ClockType:
        """This clock's type."""
        return self._clock_type

    def __repr__(self) -> str:
        return f"Clock(clock_type={self.clock_type.name})"

    def _now_ns(self) -> int:
        if self._clock_type == ClockType.STEADY_TIME:
            return time.monotonic_ns()
        return time.time_ns()

    def now(self) -> Time:
        """The current time of this clock."""
        return Time(nanoseconds=self._now_ns(), clock_type=self._clock_type)

    def create_jump_callback(
        self,
        threshold: JumpThreshold,
        *,
        pre_callback: Callable[[], None] | None = None,
        post_callback: Callable[[TimeJump], None] | None = None,
    ) -> JumpHandle:
        """Call ``pre_callback()`` before and ``post_callback(jump)`` after a jump that
        ``threshold`` selects (only a ROS clock jumps)."""
        return JumpHandle(
            clock=self, threshold=threshold, pre_callback=pre_callback, post_callback=post_callback
        )

    def sleep_until(self, until: Time, context: Context | None = None) -> bool:
        """Sleep until this clock reaches ``until``; False if woken otherwise (the context
        shut down, ROS time switched on or off)."""
        from launchkit.ros.context import NotInitializedException, default_context

        context = context or default_context
        if not context.ok():
            raise NotInitializedException()
        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        return self._wait_until(until.nanoseconds, context)

    def _wait_until(self, target_ns: int, context: Context) -> bool:
        while context.ok():
            remaining = (target_ns - self._now_ns()) / _NS
            if remaining <= 0:
                return True
            time.sleep(min(remaining, _POLL))
        return False

    def sleep_for(self, rel_time: Duration, context: Context | None = None) -> bool:
        """Sleep for ``rel_time`` of this clock (see :meth:`sleep_until`)."""
        return self.sleep_until(self.now() + rel_time, context)


class SleepWatcher(Protocol):
    """Told of every sleep on a ROS clock (a lockstep participant: the time stops at each
    wake-up, and the woken thread counts as busy until it sleeps or spins again)."""

    def sleeping(self, until_ns: int) -> None:
        """The calling thread sleeps until ``until_ns``."""

    def woke(self) -> None:
        """The calling thread's sleep ended."""


class ROSClock(Clock):
    """The clock nodes use: system time, or the time ``/clock`` sets while ROS time is active."""

    def __new__(cls, *, clock_type: ClockType = ClockType.ROS_TIME) -> ROSClock:
        return object.__new__(cls)

    def __init__(self, *, clock_type: ClockType = ClockType.ROS_TIME) -> None:
        super().__init__(clock_type=ClockType.ROS_TIME)
        self._active = False
        self._override_ns = 0
        self._changed = threading.Condition()
        self.sleep_watcher: SleepWatcher | None = None

    @property
    def ros_time_is_active(self) -> bool:
        """Whether the clock reports the time ``/clock`` set."""
        return self._active

    def _now_ns(self) -> int:
        return self._override_ns if self._active else time.time_ns()

    def _set_ros_time_is_active(self, enabled: bool) -> None:
        if enabled == self._active:
            return
        change = ClockChange.ROS_TIME_ACTIVATED if enabled else ClockChange.ROS_TIME_DEACTIVATED
        before = self._now_ns()
        self._jump(change, lambda: setattr(self, "_active", enabled), before)

    def set_ros_time_override(self, time: Time) -> None:
        """The time the clock reports while ROS time is active (what ``/clock`` says)."""
        if not isinstance(time, Time):
            raise TypeError(
                f"Time must be specified as rclpy.time.Time. Received type: {type(time)}"
            )
        self._set_override_ns(time.nanoseconds)

    def _set_override_ns(self, nanoseconds: int) -> None:
        if not self._active:
            self._override_ns = nanoseconds
            return
        before = self._override_ns

        def apply() -> None:
            self._override_ns = nanoseconds

        self._jump(ClockChange.ROS_TIME_NO_CHANGE, apply, before)

    def _jump(self, change: ClockChange, apply: Callable[[], None], before_ns: int) -> None:
        handles = [h for h in list(self._jump_handles) if _selects(h.threshold, change, None)]
        for handle in handles:
            if handle.pre_callback is not None and change != ClockChange.ROS_TIME_NO_CHANGE:
                handle.pre_callback()
        apply()
        delta = Duration(nanoseconds=self._now_ns() - before_ns)
        with self._changed:
            self._changed.notify_all()
        for handle in list(self._jump_handles):
            if handle.post_callback is not None and _selects(handle.threshold, change, delta):
                handle.post_callback(TimeJump(change, delta))

    def _wait_until(self, target_ns: int, context: Context) -> bool:
        watcher = self.sleep_watcher if self._active else None
        if watcher is None:
            return self._wait_for_time(target_ns, context)
        watcher.sleeping(target_ns)
        try:
            return self._wait_for_time(target_ns, context)
        finally:
            watcher.woke()

    def _wait_for_time(self, target_ns: int, context: Context) -> bool:
        active = self._active
        with self._changed:
            while context.ok() and self._active == active:
                if self._now_ns() >= target_ns:
                    return True
                wait = _POLL
                if not self._active:
                    wait = min(wait, max(0.0, (target_ns - self._now_ns()) / _NS))
                self._changed.wait(wait)
        return False


def _selects(threshold: JumpThreshold, change: ClockChange, delta: Duration | None) -> bool:
    if change in (ClockChange.ROS_TIME_ACTIVATED, ClockChange.ROS_TIME_DEACTIVATED):
        return threshold.on_clock_change
    if delta is None:
        return threshold.min_forward is not None or threshold.min_backward is not None
    if threshold.min_forward is not None and delta >= threshold.min_forward:
        return True
    return threshold.min_backward is not None and delta <= threshold.min_backward
