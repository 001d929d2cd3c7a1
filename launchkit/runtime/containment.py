"""Every process a launch starts, however it detaches, goes when the launch does.

A process group holds a child and what it forks, but a grandchild that calls ``setsid`` (or a
daemon that double-forks) leaves the group, and the launcher's SIGKILL of groups misses it.
Two ways to keep hold of such processes, the first that works here:

* **a cgroup** (version 2) of the launch, where the machine offers a writable one (root, a
  container, a systemd user service with delegation): each child is moved into it before its
  program runs (it waits at its gate until then), and nothing its descendants do takes them
  out. At the end, and from the orphan guard if the launcher is killed, ``cgroup.kill`` kills
  every process in it at once; the cgroup is then removed.
* **the launcher as child subreaper** (``PR_SET_CHILD_SUBREAPER``, set by ``launchkit run``,
  whose process is the launch's): an orphaned descendant is re-parented to the launcher
  instead of init, so every process of the launch stays below the launcher in the process
  tree. Without a cgroup, the launcher walks that tree every :data:`SWEEP_PERIOD` seconds for
  processes outside the groups it started (strays), tells the orphan guard their groups, and
  kills them at the end. Its limit: a stray made less than a sweep before the launcher is
  SIGKILLed is not known to the guard yet and survives. A launch run inside another program
  (``launchkit.api.run``) does not make that program a subreaper: there, without a cgroup,
  only strays still below one of the launch's processes are found (not a daemon whose parent
  exited).

The shared background router is started outside the subreaper
(:func:`launchkit.own_process.not_subreaper`): it is meant to outlive the launch.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import signal
import time
from collections.abc import Callable
from pathlib import Path

from launchkit.envvars import NO_CGROUP
from launchkit.own_process import is_subreaper, own_helpers

#: Seconds between two looks for strays when there is no cgroup.
SWEEP_PERIOD = 0.5
#: Seconds the end of a launch waits for its cgroup to empty after ``cgroup.kill``.
KILL_WAIT = 2.0


def cgroup_v2_path() -> Path | None:
    """This process's cgroup (version 2) as a folder, if the unified hierarchy is mounted."""
    mount = None
    with contextlib.suppress(OSError):
        for line in Path("/proc/self/mountinfo").read_text().splitlines():
            left, _, right = line.partition(" - ")
            if right.split(" ", 1)[0] == "cgroup2":
                mount = left.split()[4]
                break
    own = None
    with contextlib.suppress(OSError):
        for line in Path("/proc/self/cgroup").read_text().splitlines():
            if line.startswith("0::"):
                own = line[3:]
    if mount is None or own is None:
        return None
    return Path(mount) / own.lstrip("/")


class LaunchCgroup:
    """A cgroup of the launch's processes: made under this process's own, removed at the end."""

    def __init__(self, path: Path) -> None:
        self.path = path

    @classmethod
    def make(cls) -> LaunchCgroup | None:
        """A new cgroup for the launch, or None where this machine gives none."""
        if os.environ.get(NO_CGROUP):
            return None
        parent = cgroup_v2_path()
        if parent is None:
            return None
        path = parent / f"launchkit-{os.getpid()}-{secrets.token_hex(4)}"
        try:
            path.mkdir()
        except OSError:  # read-only, not ours (a login session's scope), no such folder
            return None
        if not (path / "cgroup.kill").exists():  # before Linux 5.14: no way to kill it at once
            path.rmdir()
            return None
        return cls(path)

    def add(self, pid: int) -> bool:
        """Move ``pid`` into the cgroup; False when the system refuses."""
        try:
            (self.path / "cgroup.procs").write_text(f"{pid}\n")
        except OSError:
            return False
        return True

    def members(self) -> set[int]:
        """The processes in the cgroup now."""
        try:
            return {int(pid) for pid in (self.path / "cgroup.procs").read_text().split()}
        except OSError:
            return set()

    def kill(self) -> None:
        """SIGKILL every process in the cgroup, wait for it to empty, and remove it."""
        with contextlib.suppress(OSError):
            (self.path / "cgroup.kill").write_text("1\n")
        deadline = time.monotonic() + KILL_WAIT
        while time.monotonic() < deadline:
            try:
                self.path.rmdir()
                return
            except FileNotFoundError:
                return
            except OSError:  # EBUSY: the last ones are still dying
                time.sleep(0.01)


class Containment:
    """The launch's hold on its descendants: its cgroup if it has one, the subreaper always.
    ``tell_guard(line)`` hands the orphan guard what it must kill should the launcher die."""

    def __init__(self, tell_guard: Callable[[str], None]) -> None:
        self._tell_guard = tell_guard
        self.cgroup = LaunchCgroup.make()
        if self.cgroup is not None:
            tell_guard(f"={self.cgroup.path}")
        self._groups: set[int] = set()  # the groups of the launch's own children
        self._strays: dict[int, int] = {}  # pid -> its group, outside those groups
        self._swept = 0.0

    @property
    def sweeping(self) -> bool:
        """Whether strays are looked for periodically (no cgroup holds them)."""
        return self.cgroup is None

    def adopt(self, pid: int) -> None:
        """A child the launcher started, leader of its own group and not yet running its
        program: into the cgroup."""
        self._groups.add(pid)
        if self.cgroup is not None and not self.cgroup.add(pid):
            self.cgroup.kill()  # the system refuses to move processes: do without it
            self.cgroup = None
            self._tell_guard("=")

    def sweep(self, now: float) -> None:
        """Look for strays (every :data:`SWEEP_PERIOD`): processes below the launcher, outside
        :data:`own_helpers`, in none of the launch's groups; the guard is told their groups."""
        if not self.sweeping or now - self._swept < SWEEP_PERIOD:
            return
        self._swept = now
        if is_subreaper():  # every orphan of the launch is a child of this process
            below = _descendants(os.getpid(), own_helpers)
        else:  # a program that runs a launch among other things: below its processes only
            below = set().union(*(_descendants(leader, own_helpers) for leader in self._groups))
        for pid in below - self._strays.keys():
            try:
                group = os.getpgid(pid)
            except OSError:
                continue  # gone meanwhile
            if group not in self._groups:
                self._strays[pid] = group
                self._tell_guard(str(group))

    def kill_all(self) -> None:
        """The launch is over: kill what is left of it (a ``setsid`` grandchild, a daemon)."""
        if self.cgroup is not None:
            killed = self.cgroup.members()
            self.cgroup.kill()
            self.cgroup = None
        else:
            self._swept = 0.0
            self.sweep(time.monotonic() + SWEEP_PERIOD)
            killed = set(self._strays)
            for pid, group in self._strays.items():
                with contextlib.suppress(OSError):
                    os.killpg(group, signal.SIGKILL)
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
        for pid in killed & _children(os.getpid()):
            _reap(pid)  # re-parented to the launcher: reap it, no zombie stays
        self._strays.clear()


def _descendants(root: int, skip: set[int]) -> set[int]:
    """Every process below ``root`` in the process tree, but ``skip`` and what is below them."""
    found: set[int] = set()
    todo = [root]
    while todo:
        for child in _children(todo.pop()) - skip - found:
            found.add(child)
            todo.append(child)
    return found


def _children(pid: int) -> set[int]:
    """The pids of ``pid``'s children (of any of its threads)."""
    found: set[int] = set()
    with contextlib.suppress(OSError):
        for task in Path(f"/proc/{pid}/task").iterdir():
            with contextlib.suppress(OSError):
                found.update(int(pid) for pid in (task / "children").read_text().split())
    return found


def _reap(pid: int) -> None:
    """Wait (at most :data:`KILL_WAIT`) for a SIGKILLed child to be gone, and reap it."""
    deadline = time.monotonic() + KILL_WAIT
    while time.monotonic() < deadline:
        try:
            if os.waitpid(pid, os.WNOHANG)[0]:
                return
        except (ChildProcessError, OSError):
            return
        time.sleep(0.005)
