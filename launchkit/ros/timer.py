"""Timers, run by the executor of their node when due (rclpy's ``Timer``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.ros.clock import Clock
from launchkit.ros.task import await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup

_NS = 1_000_000_000


class Timer:
    """Calls ``callback`` every period of ``clock`` (sim time when the clock follows it).

    A callback may be a coroutine function. Created stopped with ``autostart=False``;
    ``reset()`` starts it.
    """

    def __init__(
        self,
        callback: Callable[[], Any] | None,
        period_sec: float,
        clock: Clock,
        callback_group: CallbackGroup | None = None,
        *,
        autostart: bool = True,
    ) -> None:
        if period_sec < 0:
            raise ValueError(f"timer period must be >= 0, got {period_sec}")
        self.callback = callback
        self._period_ns = int(float(period_sec) * _NS)
        self._clock = clock
        self.callback_group: Any = callback_group
        self._executor_event = False  # an executor's handler for it is pending
        self._canceled = not autostart
        self._destroyed = False
        self._last_ns = clock.now().nanoseconds
        self._next_ns = self._last_ns + self._period_ns

    @property
    def clock(self) -> Clock:
        """The clock the period is measured on."""
        return self._clock

    @property
    def timer_period_ns(self) -> int:
        """The period in nanoseconds (settable: the next call is one new period from now)."""
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value: int) -> None:
        self._period_ns = int(value)
        self.reset()

    def is_canceled(self) -> bool:
        """Whether the timer is stopped."""
        return self._canceled

    def cancel(self) -> None:
        """Stop calling back (``reset()`` restarts)."""
        self._canceled = True

    def reset(self) -> None:
        """(Re)start: the next call is one period from now."""
        self._canceled = False
        self._next_ns = self._clock.now().nanoseconds + self._period_ns

    def time_since_last_call(self) -> int:
        """Nanoseconds since the last call (or since the timer was made)."""
        return self._clock.now().nanoseconds - self._last_ns

    def time_until_next_call(self) -> int | None:
        """Nanoseconds until due (<= 0 means due now); None when canceled."""
        if self._canceled or self._destroyed:
            return None
        return self._next_ns - self._clock.now().nanoseconds

    def is_ready(self) -> bool:
        """Whether the timer is due."""
        remaining = self.time_until_next_call()
        return remaining is not None and remaining <= 0

    def _call(self) -> bool:
        """Count a call now: the next one is a period later (missed periods are skipped, as
        rcl does). False when the timer is not due."""
        if not self.is_ready():
            return False
        now = self._clock.now().nanoseconds
        self._last_ns = now
        self._next_ns += self._period_ns
        if self._next_ns <= now:  # fell behind (or sim time jumped)
            if self._period_ns:
                missed = (now - self._next_ns) // self._period_ns + 1
                self._next_ns += missed * self._period_ns
            else:
                self._next_ns = now
        return True

    def _take_for_executor(self) -> Callable[[], Any] | None:
        if not self._call() or self.callback is None:
            return None
        callback = self.callback

        async def execute() -> None:
            await await_or_execute(callback)

        return execute

    def destroy(self) -> None:
        """Stop for good."""
        self._destroyed = True
        self._canceled = True
