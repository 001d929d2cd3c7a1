"""``Rate``: sleep so that a loop runs at a fixed frequency of a clock (rclpy's ``Rate``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.ros.clock import Clock, Time

if TYPE_CHECKING:
    from launchkit.ros.context import Context

_NS = 1_000_000_000


class Rate:
    """Call ``sleep()`` once per loop to run at ``frequency`` Hz.

    Unlike rclpy's, it needs no executor spinning in another thread: it sleeps on its clock
    (and wakes early when the context shuts down).
    """

    def __init__(self, frequency: float, clock: Clock, *, context: Context | None = None) -> None:
        if frequency <= 0:
            raise ValueError(f"rate frequency must be > 0, got {frequency}")
        self.period_ns = int(_NS / frequency)
        self.clock = clock
        self.context = context
        self._next = clock.now().nanoseconds + self.period_ns
        self._destroyed = False

    def sleep(self) -> None:
        """Sleep until the next period starts (no sleep if the loop is already late)."""
        if self._destroyed:
            raise RuntimeError("Rate was destroyed")
        now = self.clock.now().nanoseconds
        if self._next > now:
            # until the period's own instant: a sleep_for would read the clock again, and on a
            # clock that moves meanwhile (sim time) end that much later
            until = Time(nanoseconds=self._next, clock_type=self.clock.clock_type)
            self.clock.sleep_until(until, self.context)
            self._next += self.period_ns
        else:
            self._next = now + self.period_ns

    def destroy(self) -> None:
        """Stop: a later ``sleep()`` is an error."""
        self._destroyed = True
