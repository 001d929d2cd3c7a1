"""A watchdog that kills every child process group if the launcher dies without cleaning up.

``PR_SET_PDEATHSIG`` reaches only direct children, and nothing runs in a process that was
SIGKILLed. So the launcher starts one tiny ``sh`` in its own session, tells it each child's
process group over a pipe (and each group that is gone again, so that a reused id is never
killed), and kills it on a clean exit. If the launcher dies any other way the pipe closes,
``read`` returns, and the watchdog SIGKILLs every group it still knows, grandchildren of
``sh -c`` included, kills the launch's cgroup (:mod:`launchkit.runtime.containment`: what
left its group too), and removes the folder it was told about (the launcher's private run folder:
the child-request socket, generated parameter files, the plugin files of its processes).

A child's program does not start before the watchdog knows its group (see
:func:`launchkit.runtime.process.gated`), so no SIGKILL of the launcher can fall between the
two.
"""

from __future__ import annotations

import os
import signal
import subprocess

from launchkit.own_process import own_helpers

# Groups are kept in one string " g1 g2 ... " so that a line "-g" can take one out without a
# fork: ${gs%% g *} is what comes before it, ${gs#* g } what comes after.
# A line "=/sys/fs/cgroup/..." names the launch's cgroup ("=" alone: none any more), killed
# whole with cgroup.kill and removed once empty.
_SCRIPT = (
    'trap "" INT TERM HUP QUIT; d=""; c=""; gs=" "; '
    'while read -r g; do case "$g" in '
    '/*) d="$g";; '
    '=*) c="${g#=}";; '
    '-*) g="${g#-}"; case "$gs" in *" $g "*) gs="${gs%% $g *} ${gs#* $g }";; esac;; '
    '*) gs="$gs$g ";; '
    "esac; done; "
    '[ -z "$c" ] || echo 1 > "$c/cgroup.kill"; '
    'for g in $gs; do kill -9 "-$g" 2>/dev/null; done; '
    '[ -z "$d" ] || rm -rf "$d"; '
    '[ -z "$c" ] || for i in 1 2 3 4 5 6 7 8 9 10; do rmdir "$c" 2>/dev/null && break; '
    "sleep 0.2; done"
)


class OrphanGuard:
    """The watchdog process; started on the first child, dismissed on a clean exit."""

    def __init__(self) -> None:
        self._process: subprocess.Popen[bytes] | None = None

    def watch(self, pgid: int) -> None:
        """Add a process group to kill should the launcher die."""
        self._tell(str(pgid))

    def forget(self, pgid: int) -> None:
        """A process group is empty now: its id may be reused, never kill it."""
        if self._process is not None:
            self._tell(f"-{pgid}")

    @property
    def pid(self) -> int | None:
        """The watchdog's pid, once started."""
        return None if self._process is None else self._process.pid

    def tell(self, line: str) -> None:
        """Tell the watchdog one line of its script's language (a cgroup: ``=PATH``)."""
        self._tell(line)

    def remove_on_death(self, folder: str) -> None:
        """The folder (an absolute path) to remove should the launcher die."""
        self._tell(folder)

    def _tell(self, line: str) -> None:
        if self._process is None:
            self._process = subprocess.Popen(
                ["/bin/sh", "-c", _SCRIPT],
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,
                close_fds=True,
            )
            own_helpers.add(self._process.pid)
        assert self._process.stdin is not None
        try:
            self._process.stdin.write(f"{line}\n".encode())
            self._process.stdin.flush()
        except OSError:
            pass  # the guard died (someone killed it); the launcher's own cleanup still runs

    def dismiss(self) -> None:
        """Stop the watchdog without it killing anything (every child is already gone)."""
        if self._process is None:
            return
        try:
            os.kill(self._process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self._process.wait()
        own_helpers.discard(self._process.pid)
        if self._process.stdin is not None:
            try:
                self._process.stdin.close()
            except OSError:
                pass
        self._process = None
