"""A watchdog that kills every child process group if the launcher dies without cleaning up.

``PR_SET_PDEATHSIG`` reaches only direct children, and nothing runs in a process that was
SIGKILLed. So the launcher starts one tiny ``sh`` in its own session, tells it each child's
process group over a pipe, and kills it on a clean exit. If the launcher dies any other way the
pipe closes, ``read`` returns, and the watchdog SIGKILLs every group it was told about,
grandchildren of ``sh -c`` included, and removes the folder it was told about (that of the
launcher's child-request socket).
"""

from __future__ import annotations

import os
import signal
import subprocess

_SCRIPT = (
    'trap "" INT TERM HUP QUIT; d=""; '
    'while read -r g; do case "$g" in /*) d="$g";; *) set -- "$@" "$g";; esac; done; '
    'for g in "$@"; do kill -9 "-$g" 2>/dev/null; done; '
    '[ -z "$d" ] || rm -rf "$d"'
)


class OrphanGuard:
    """The watchdog process; started on the first child, dismissed on a clean exit."""

    def __init__(self) -> None:
        self._process: subprocess.Popen[bytes] | None = None

    def watch(self, pgid: int) -> None:
        """Add a process group to kill should the launcher die."""
        self._tell(str(pgid))

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
        if self._process.stdin is not None:
            try:
                self._process.stdin.close()
            except OSError:
                pass
        self._process = None
