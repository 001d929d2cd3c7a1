"""The supervisor's hooks of a lockstep launch: the launch's clock hears of every process.

The time authority (``launchkit.ros.lockstep.authority``) holds the simulated time while a
process it was told of has not joined, and forgets a process's participants when it exits.
Every event also goes on to the hooks the launch had already (the test plugin's channel).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from launchkit.runtime.hooks import SupervisorHooks

if TYPE_CHECKING:
    from launchkit.runtime.process import SupervisedProcess


class ProcessWatcher(Protocol):
    """What the hooks tell the clock."""

    def expect(self, pid: int, label: str) -> None:
        """A process started."""

    def exited(self, pid: int) -> None:
        """A process exited."""

    def launch_ready(self) -> None:
        """Every process the launch starts at once has been started."""


class ClockHooks(SupervisorHooks):
    """Tells ``clock`` of processes started and exited; passes every event on to ``inner``."""

    def __init__(self, clock: ProcessWatcher, inner: SupervisorHooks | None) -> None:
        self.clock = clock
        self.inner = inner or SupervisorHooks()

    def launch_ready(self) -> None:
        """The clock may start; passed on."""
        self.clock.launch_ready()
        self.inner.launch_ready()

    def launch_error(self, message: str) -> None:
        """Passed on."""
        self.inner.launch_error(message)

    def process_started(self, process: SupervisedProcess) -> None:
        """The clock waits for it; passed on."""
        if process.pid is not None:
            self.clock.expect(process.pid, process.label)
        self.inner.process_started(process)

    def process_output(self, process: SupervisedProcess, stream: str, line: str) -> None:
        """Passed on."""
        self.inner.process_output(process, stream, line)

    def process_stopping(self, process: SupervisedProcess) -> None:
        """Passed on."""
        self.inner.process_stopping(process)

    def process_exited(self, process: SupervisedProcess, returncode: int) -> None:
        """The clock forgets it; passed on."""
        if process.pid is not None:
            self.clock.exited(process.pid)
        self.inner.process_exited(process, returncode)

    def shutdown(self, reason: str) -> None:
        """Passed on."""
        self.inner.shutdown(reason)
