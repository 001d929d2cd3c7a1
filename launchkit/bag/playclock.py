"""The player's clock: bag time against the steady clock, with rate, pause, step and jumps."""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable


class Wait(enum.Enum):
    """How a wait for a message's time ended."""

    DUE = "due"  # its time has come
    STEP = "step"  # paused, and the user asked for the next message
    STOPPED = "stopped"


class PlaybackClock:
    """Maps bag time (ns) to the steady clock: ``bag = anchor_bag + (now - anchor) * rate``.

    Pausing freezes bag time; resuming, a new rate or a jump re-anchors it, so playback goes on
    from where it is. Every change wakes a waiting player at once.
    """

    def __init__(
        self,
        start: int,
        rate: float = 1.0,
        paused: bool = False,
        steady: Callable[[], int] = time.monotonic_ns,
    ) -> None:
        self._steady = steady  # the steady clock (ns); a test passes its own
        self._cond = threading.Condition()
        self._rate = rate
        self._anchor = steady()
        self._anchor_bag = start
        self._paused = paused
        self._step = False
        self._stopped = False

    # reading ----------------------------------------------------------------------------
    def now(self) -> int:
        """The current bag time."""
        with self._cond:
            return self._now(self._steady())

    def _now(self, steady: int) -> int:
        if self._paused:
            return self._anchor_bag
        return self._anchor_bag + int((steady - self._anchor) * self._rate)

    @property
    def rate(self) -> float:
        """Bag seconds per steady second."""
        return self._rate

    @property
    def paused(self) -> bool:
        """Whether bag time is frozen."""
        return self._paused

    # changing ---------------------------------------------------------------------------
    def _reanchor(self, bag_time: int | None = None) -> None:
        steady = self._steady()
        self._anchor_bag = self._now(steady) if bag_time is None else bag_time
        self._anchor = steady
        self._cond.notify_all()

    def _set_paused(self, paused: bool) -> None:
        # anchor at the current bag time first, under the old state, then switch
        self._reanchor()
        self._paused = paused

    def pause(self) -> None:
        """Freeze bag time."""
        with self._cond:
            self._set_paused(True)

    def resume(self) -> None:
        """Let bag time run again from where it stopped."""
        with self._cond:
            self._set_paused(False)

    def toggle(self) -> bool:
        """Pause or resume; True if now paused."""
        with self._cond:
            self._set_paused(not self._paused)
            return self._paused

    def set_rate(self, rate: float) -> None:
        """Play at ``rate`` from now on (bag time does not jump)."""
        if rate <= 0:
            raise ValueError("the rate must be positive")
        with self._cond:
            self._reanchor()
            self._rate = rate

    def jump(self, bag_time: int) -> None:
        """Set bag time to ``bag_time`` (a step, a loop, a start offset)."""
        with self._cond:
            self._reanchor(bag_time)

    def step(self) -> bool:
        """While paused: let the next message go now. False (nothing done) when playing."""
        with self._cond:
            if not self._paused:
                return False
            self._step = True
            self._cond.notify_all()
            return True

    def stop(self) -> None:
        """End every wait."""
        with self._cond:
            self._stopped = True
            self._cond.notify_all()

    # waiting ----------------------------------------------------------------------------
    def wait_until(self, bag_time: int) -> Wait:
        """Block until bag time reaches ``bag_time``, a step is asked for, or a stop."""
        with self._cond:
            while True:
                if self._stopped:
                    return Wait.STOPPED
                if self._paused:
                    if self._step:
                        self._step = False
                        return Wait.STEP
                    self._cond.wait()
                    continue
                steady = self._steady()
                remaining = (bag_time - self._now(steady)) / self._rate
                if remaining <= 0:
                    return Wait.DUE
                self._cond.wait(remaining / 1e9)
