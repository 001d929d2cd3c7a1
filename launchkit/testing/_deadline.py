"""Deadlines for waits, scaled by ``LAUNCHKIT_TIMEOUT_SCALE`` for slow machines."""

from __future__ import annotations

import os
import time

from launchkit.envvars import TIMEOUT_SCALE as TIMEOUT_SCALE_ENV


def timeout_scale() -> float:
    """The factor every deadline is multiplied by (``LAUNCHKIT_TIMEOUT_SCALE``, default 1)."""
    text = os.environ.get(TIMEOUT_SCALE_ENV, "").strip()
    if not text:
        return 1.0
    try:
        scale = float(text)
    except ValueError:
        scale = -1.0
    if not scale > 0:
        raise ValueError(f"{TIMEOUT_SCALE_ENV}={text!r}: expected a positive number such as 2.5")
    return scale


def scaled(seconds: float) -> float:
    """``seconds`` multiplied by the timeout scale."""
    return seconds * timeout_scale()


class Deadline:
    """A point in monotonic time ``seconds`` (scaled) from now."""

    def __init__(self, seconds: float) -> None:
        self.seconds = scaled(seconds)
        self._end = time.monotonic() + self.seconds

    def remaining(self) -> float:
        """Seconds left (never negative)."""
        return max(0.0, self._end - time.monotonic())

    def expired(self) -> bool:
        """Whether the deadline has passed."""
        return time.monotonic() >= self._end

    def renewed(self) -> Deadline:
        """A deadline of the same (already scaled) length, starting now."""
        fresh = Deadline.__new__(Deadline)
        fresh.seconds = self.seconds
        fresh._end = time.monotonic() + self.seconds
        return fresh
