"""What a launch leaves behind that must go however it ends: its process groups and its
private run folder, with the orphan guard behind both for when the launcher is killed.

A child's process group is watched from its start. When its leader exits, the group is
forgotten if it is empty; otherwise its leftovers (grandchildren) are killed before the process
is started again, at shutdown, or at the latest when the launcher exits. The run folder (mode
0700) holds the child-request socket, generated parameter files and whatever the launch's
processes put in ``$LAUNCHKIT_RUN_TMPDIR``.
"""

from __future__ import annotations

import shutil
import signal
import tempfile

from launchkit.runtime.orphan_guard import OrphanGuard
from launchkit.runtime.process import SupervisedProcess, kill_group


class LaunchCleanup:
    """The launch's process groups and run folder (also the context's ``child_groups``)."""

    def __init__(self) -> None:
        self._guard = OrphanGuard()
        self._lingering: set[int] = set()
        self.folder: str | None = None

    def open_folder(self) -> str:
        """Create the run folder; the guard removes it should the launcher die."""
        self.folder = tempfile.mkdtemp(prefix="launchkit-")
        self._guard.remove_on_death(self.folder)
        return self.folder

    def watch(self, pgid: int) -> None:
        """A new process group (a child, or a ``$(command)``)."""
        self._guard.watch(pgid)

    def forget(self, pgid: int) -> None:
        """A process group that is empty now."""
        self._lingering.discard(pgid)
        self._guard.forget(pgid)

    def exited(self, process: SupervisedProcess, *, shutting_down: bool) -> None:
        """``process``'s incarnation exited: forget its group, or note (or, while shutting
        down, kill) what is left in it."""
        pid = process.pid
        if pid is None:
            return
        if not process.group_alive():
            self.forget(pid)
        elif shutting_down:
            process.kill_leftovers()
        else:
            self._lingering.add(pid)

    def before_respawn(self, process: SupervisedProcess) -> None:
        """Kill what ``process``'s last incarnation left in its group."""
        pid = process.pid
        if pid is None:
            return
        if process.group_alive():
            process.kill_leftovers()
        self.forget(pid)

    def close(self) -> None:
        """The launch is over (every child was reaped): kill the leftovers, dismiss the guard,
        remove the folder."""
        for pgid in self._lingering:
            kill_group(pgid, signal.SIGKILL)
        self._lingering.clear()
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None
        self._guard.dismiss()  # last: until here, a SIGKILL of the launcher still cleans up
