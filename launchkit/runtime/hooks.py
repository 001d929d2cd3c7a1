"""Observers of a running launch: the supervisor tells a :class:`SupervisorHooks` what happens.

The base class does nothing, so a supervisor without observers behaves exactly as before.
``launchkit.runtime.events`` implements it to stream the launch's life to a test process.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launchkit.runtime.process import SupervisedProcess


class SupervisorHooks:
    """Called by the supervisor, on its loop, as the launch goes; every method is optional."""

    def launch_ready(self) -> None:
        """The first pass is done: every process the file starts at once has been started."""

    def launch_error(self, message: str) -> None:
        """Something failed while running (already reported on screen); shutdown follows,
        but for a process whose working folder is missing (which fails alone, as in ROS)."""

    def process_started(self, process: SupervisedProcess) -> None:
        """``process`` has a new incarnation (a first start or a respawn) with a pid."""

    def process_output(self, process: SupervisedProcess, stream: str, line: str) -> None:
        """``process`` wrote ``line`` on ``stream`` (``stdout`` or ``stderr``)."""

    def process_stopping(self, process: SupervisedProcess) -> None:
        """``process`` alone is being stopped on request (the launch goes on); its exit that
        follows is expected."""

    def process_exited(self, process: SupervisedProcess, returncode: int) -> None:
        """``process`` exited (negative ``returncode``: killed by that signal)."""

    def shutdown(self, reason: str) -> None:
        """The launch started shutting down."""
