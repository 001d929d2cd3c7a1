"""Pacing sim time to wall time at a real-time factor."""

from __future__ import annotations

import time
from collections.abc import Callable


class Pacer:
    """Says how long to wait so that sim time runs ``real_time_factor`` × wall time.

    A factor of 0 (or below) means "as fast as possible". After a stall longer than
    ``max_lag`` seconds the pacer re-anchors instead of racing to catch up.
    """

    def __init__(
        self,
        real_time_factor: float = 1.0,
        *,
        clock: Callable[[], float] = time.monotonic,
        max_lag: float = 0.25,
    ) -> None:
        self.factor = real_time_factor
        self.clock = clock
        self.max_lag = max_lag
        self._anchor_wall: float | None = None
        self._anchor_sim = 0.0

    def wait_needed(self, sim_time: float) -> float:
        """Seconds of wall time to wait before sim time ``sim_time`` is due (0 if late)."""
        if self.factor <= 0:
            return 0.0
        now = self.clock()
        if self._anchor_wall is None:
            self._anchor_wall, self._anchor_sim = now, sim_time
            return 0.0
        due = self._anchor_wall + (sim_time - self._anchor_sim) / self.factor
        if now - due > self.max_lag:
            self._anchor_wall, self._anchor_sim = now, sim_time
            return 0.0
        return max(0.0, due - now)
