"""Finding and ending what is left of a launch, through ``/proc``.

Every process the launcher starts leads its own session (``start_new_session``), and so does
the launcher itself: anything in one of those sessions or process groups belongs to the launch,
``sh -c`` grandchildren included, even after its parent is gone.
"""

from __future__ import annotations

import os
import select
import signal
import threading
from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

from launchkit.testing._deadline import Deadline

_PROC = Path("/proc")
_POLL = 0.02  # only without pidfds


@dataclass(frozen=True)
class LiveProcess:
    """A live process found in ``/proc``."""

    pid: int
    pgid: int
    sid: int
    cmdline: str

    def __str__(self) -> str:
        return f"pid {self.pid} (group {self.pgid}, session {self.sid}): {self.cmdline}"


def _read_stat(pid_dir: Path) -> tuple[str, int, int] | None:
    """(state, pgid, sid) of a process, or None if it is gone."""
    try:
        stat = (pid_dir / "stat").read_text()
    except OSError:
        return None
    # the command name may hold spaces and parentheses: fields follow the last ')'
    fields = stat[stat.rfind(")") + 2 :].split()
    return fields[0], int(fields[2]), int(fields[3])


def _cmdline(pid_dir: Path) -> str:
    try:
        raw = (pid_dir / "cmdline").read_bytes()
    except OSError:
        return "?"
    return raw.replace(b"\0", b" ").decode(errors="replace").strip() or "?"


def members(groups: Collection[int]) -> list[LiveProcess]:
    """Live (not zombie) processes whose session or process group is in ``groups``."""
    wanted = set(groups)
    found: list[LiveProcess] = []
    if not wanted:
        return found
    me = os.getpid()
    for pid_dir in _PROC.iterdir():
        if not pid_dir.name.isdigit() or int(pid_dir.name) == me:
            continue
        stat = _read_stat(pid_dir)
        if stat is None:
            continue
        state, pgid, sid = stat
        if state in ("Z", "X"):
            continue  # dead, waiting to be reaped: nothing runs
        if sid in wanted or pgid in wanted:
            found.append(LiveProcess(int(pid_dir.name), pgid, sid, _cmdline(pid_dir)))
    return found


def kill_groups(groups: Collection[int], signum: int = signal.SIGKILL) -> None:
    """Send ``signum`` to each process group in ``groups`` and to every member found."""
    for pgid in groups:
        try:
            os.killpg(pgid, signum)
        except (ProcessLookupError, PermissionError):
            pass
    for process in members(groups):
        try:
            os.kill(process.pid, signum)
        except (ProcessLookupError, PermissionError):
            pass


def wait_gone(processes: Collection[LiveProcess], deadline: Deadline) -> list[LiveProcess]:
    """Wait (through pidfds) until ``processes`` have exited or ``deadline`` passes; those
    still alive then."""
    waiting: dict[int, LiveProcess] = {}
    unwatched: list[LiveProcess] = []
    for process in processes:
        try:
            fd = os.pidfd_open(process.pid)
        except ProcessLookupError:
            continue  # already gone
        except OSError:
            unwatched.append(process)  # a kernel without pidfds (before Linux 5.3)
            continue
        waiting[fd] = process
    if unwatched:
        _poll_gone(unwatched, deadline)
    try:
        while waiting and not deadline.expired():
            ready, _, _ = select.select(list(waiting), [], [], deadline.remaining())
            for fd in ready:
                os.close(fd)
                del waiting[fd]
        still = list(waiting.values())
    finally:
        for fd in waiting:
            os.close(fd)
    # a pidfd turns readable only once the process is reaped or a zombie; re-check state
    return [p for p in [*still, *unwatched] if _alive(p.pid)]


def _poll_gone(processes: list[LiveProcess], deadline: Deadline) -> None:
    pause = threading.Event()
    while any(_alive(p.pid) for p in processes) and not deadline.expired():
        pause.wait(min(_POLL, deadline.remaining()))


def _alive(pid: int) -> bool:
    stat = _read_stat(_PROC / str(pid))
    return stat is not None and stat[0] not in ("Z", "X")


def sweep(groups: Collection[int], grace: Deadline) -> list[LiveProcess]:
    """What is left of ``groups`` once ``grace`` has passed (processes already killed get that
    long to go); those are SIGKILLed, and returned so the caller can report them."""
    survivors = members(groups)
    if survivors:
        survivors = wait_gone(survivors, grace)
    if survivors:
        kill_groups(groups, signal.SIGKILL)
        wait_gone(survivors, grace.renewed())  # the grace above is spent: wait for the kill
    return survivors
