"""Timers, run by the executor in the spinning thread."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.ros.clock import Clock

_NS = 1_000_000_000


class Timer:
    """Calls ``callback`` every ``period`` of ``clock`` (sim time when the clock follows it)."""

    def __init__(self, callback: Callable[[], Any] | None, period_sec: float, clock: Clock) -> None:
        if period_sec < 0:
            raise ValueError(f"timer period must be >= 0, got {period_sec}")
        self.callback = callback
        self.timer_period_ns = int(period_sec * _NS)
        self.clock = clock
        self._canceled = False
        self._next_ns = clock.now().nanoseconds + self.timer_period_ns

    def is_canceled(self) -> bool:
        """Whether the timer is stopped."""
        return self._canceled

    def cancel(self) -> None:
        """Stop calling back (``reset()`` restarts)."""
        self._canceled = True

    def reset(self) -> None:
        """Restart: the next call is one period from now."""
        self._canceled = False
        self._next_ns = self.clock.now().nanoseconds + self.timer_period_ns

    def time_until_next_call(self) -> int | None:
        """Nanoseconds until due (<= 0 means due now); None when canceled."""
        if self._canceled:
            return None
        return self._next_ns - self.clock.now().nanoseconds

    def is_ready(self) -> bool:
        """Whether the timer is due."""
        remaining = self.time_until_next_call()
        return remaining is not None and remaining <= 0

    def _fire(self) -> None:
        now = self.clock.now().nanoseconds
        self._next_ns += self.timer_period_ns
        if self._next_ns <= now:  # fell behind (or sim time jumped): skip missed periods
            if self.timer_period_ns:
                missed = (now - self._next_ns) // self.timer_period_ns + 1
                self._next_ns += missed * self.timer_period_ns
            else:
                self._next_ns = now
        if self.callback is not None:
            self.callback()

    def destroy(self) -> None:
        """Cancel for good."""
        self._canceled = True
