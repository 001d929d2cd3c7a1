"""``Rate``: sleep so that a loop runs at a fixed frequency."""

from __future__ import annotations

import time

from launchkit.ros.clock import Clock, Duration

_NS = 1_000_000_000


class Rate:
    """Call ``sleep()`` once per loop to run at ``frequency`` Hz (steady clock by default)."""

    def __init__(self, frequency: float, clock: Clock) -> None:
        if frequency <= 0:
            raise ValueError(f"rate frequency must be > 0, got {frequency}")
        self.period_ns = int(_NS / frequency)
        self.clock = clock
        self._next = clock.now().nanoseconds + self.period_ns

    def sleep(self) -> None:
        """Sleep until the next period starts (no sleep if the loop is already late)."""
        now = self.clock.now().nanoseconds
        if self._next > now:
            self.clock.sleep_for(Duration(nanoseconds=self._next - now))
            self._next += self.period_ns
        else:
            self._next = now + self.period_ns

    def destroy(self) -> None:
        """Nothing to release (rclpy has it)."""
        time.sleep(0)
