"""The launcher's side of ``launchkit run --lockstep``: its time authority, made when the
launch's router is up, told of the processes the launch starts and sees exit."""

from __future__ import annotations

from collections.abc import Callable

from launchkit.ros.lockstep.authority import ClockOptions, TimeAuthority

__all__ = ["ClockOptions", "LaunchClock"]


class LaunchClock:
    """The launch's simulated clock: a :class:`TimeAuthority` once :meth:`start` is called."""

    def __init__(self, options: ClockOptions) -> None:
        self.options = options
        self._authority: TimeAuthority | None = None

    def start(
        self, router: str, log: Callable[[str, str], None], on_until: Callable[[], None]
    ) -> None:
        """Start publishing ``/clock`` on ``router``; ``log(level, message)`` says what it
        decides, ``on_until()`` is called (from its thread) at ``--until``."""
        self._authority = TimeAuthority(router, self.options, log, on_until)
        self._authority.start()
        pace = f"at most {self.options.rtf:g}x real time" if self.options.rtf else "unpaced"
        log("INFO", f"lockstep: every node runs on the launch's simulated clock ({pace})")

    def expect(self, pid: int, label: str) -> None:
        """The launch started ``pid``: the time waits for it to join."""
        if self._authority is not None:
            self._authority.expect(pid, label)

    def launch_ready(self) -> None:
        """The launch started what it starts at once."""
        if self._authority is not None:
            self._authority.launch_ready()

    def exited(self, pid: int) -> None:
        """``pid`` exited."""
        if self._authority is not None:
            self._authority.exited(pid)

    def close(self) -> None:
        """Stop the clock."""
        if self._authority is not None:
            self._authority.close()
            self._authority = None
