"""The build's child processes (pip, the setup.py reader): each runs in its own process group
with its output appended to the package's log file; all of them stop when the build is
interrupted, and the runtime's orphan guard kills them if launchkit dies any other way.

As the runtime starts a launch's processes, a child is *gated*: ``/bin/sh`` waits for one line
before it execs the command, and the line is written once the guard knows the child's group.
"""

from __future__ import annotations

import os
import signal
import subprocess
import threading
from collections.abc import Mapping
from pathlib import Path

from launchkit.runtime.orphan_guard import OrphanGuard

#: How long a child has to end after SIGTERM before it is killed.
TERMINATE_GRACE = 3.0
_GATE = 'read -r _ || exit 125; exec "$0" "$@" </dev/null'


class ChildProcesses:
    """Starts the build's commands and remembers the running ones."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._running: set[subprocess.Popen[bytes]] = set()
        self._stopping = False
        self._guard = OrphanGuard()

    def run(self, argv: list[str], cwd: Path, log: Path, env: Mapping[str, str]) -> int:
        """Run ``argv`` in ``cwd`` (no input; stdout and stderr appended to ``log``); its
        exit status, or -SIGTERM if the build is being stopped."""
        log.parent.mkdir(parents=True, exist_ok=True)
        with open(log, "ab") as output:
            output.write(("$ " + " ".join(argv) + "\n").encode())
            output.flush()
            process = self._start(argv, cwd, output.fileno(), env)
            if process is None:
                return -signal.SIGTERM
            try:
                return process.wait()
            finally:
                with self._lock:
                    self._running.discard(process)
                    self._guard.forget(process.pid)

    def _start(
        self, argv: list[str], cwd: Path, output: int, env: Mapping[str, str]
    ) -> subprocess.Popen[bytes] | None:
        gate_r, gate_w = os.pipe()
        try:
            with self._lock:  # the guard is not thread-safe; one worker at a time tells it
                if self._stopping:
                    return None
                process = subprocess.Popen(
                    ["/bin/sh", "-c", _GATE, *argv],
                    cwd=cwd,
                    env=dict(env),
                    stdin=gate_r,
                    stdout=output,
                    stderr=subprocess.STDOUT,
                    start_new_session=True,
                    close_fds=True,
                )
                self._running.add(process)
                self._guard.watch(process.pid)
            try:
                os.write(gate_w, b"\n")
            except OSError:
                pass  # it is gone already (stopped by stop_all)
        finally:
            os.close(gate_r)
            os.close(gate_w)
        return process

    def stop_all(self) -> None:
        """Stop every running command and its children (SIGTERM, then SIGKILL), and refuse
        to start more."""
        with self._lock:
            self._stopping = True
            running = list(self._running)
        for process in running:
            _signal_group(process, signal.SIGTERM)
        for process in running:
            try:
                process.wait(TERMINATE_GRACE)
            except subprocess.TimeoutExpired:
                _signal_group(process, signal.SIGKILL)
                process.wait()

    def close(self) -> None:
        """Dismiss the orphan guard (call once no command runs any more)."""
        with self._lock:
            self._guard.dismiss()


def _signal_group(process: subprocess.Popen[bytes], signum: int) -> None:
    try:
        os.killpg(process.pid, signum)
    except ProcessLookupError:
        pass
