"""A process of the launch that runs on another host, as the launcher's supervisor sees it.

It implements :class:`~launchkit.runtime.process.SupervisedProcess`, so the supervisor treats
it like a local child: its :class:`~launchkit.runtime.lifecycle.Lifecycle` decides respawns
and the stop ladder, its output lines get the usual ``[name-N]`` prefix, its exit is reported
the usual way. The agent's events arrive on Zenoh threads and are written into local pipes,
which the supervisor's selector watches as it watches a child's output and pidfd: the output
pipes for lines, and an exit pipe that becomes readable when the process has exited.

When the agent cannot be reached any more, the process is given up: after a SIGKILL the agent
does not confirm, or after the grace period without its agent (which stops it by itself then),
it counts as exited with status 255 (as ssh reports a lost connection), saying why.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from typing import Any, Protocol

from launchkit.description.process_spec import ProcessSpec
from launchkit.runtime.process import ProcessPipes

LOST = 255  # the exit status of a process whose agent was lost
KILL_WAIT = 5.0  # seconds to wait for the agent to confirm a SIGKILL


class Agents(Protocol):
    """What a remote process asks of the launch's link to the agents
    (:class:`launchkit.remote.hosts.RemoteHosts`)."""

    def start(self, process: RemoteProcess) -> int:
        """Have the agent start the process's new incarnation; its pid (``OSError``)."""

    def signal(self, process: RemoteProcess, signum: int) -> None:
        """Have the agent signal the process's group."""


class RemoteProcess(ProcessPipes):
    """One process of the launch on host ``spec.machine``, run by its agent."""

    def __init__(self, hosts: Agents, spec: ProcessSpec, label: str, index: int) -> None:
        super().__init__(spec, label, index)
        self.machine = spec.machine
        self.incarnation = 0
        self.instance = ""  # the agent run that runs the current incarnation
        self._hosts = hosts
        self._pid: int | None = None
        self._code: int | None = None
        self._writers: dict[str, int] = {}
        self._exit_w: int | None = None
        self._lock = threading.Lock()
        self._done = threading.Event()
        self._timer: threading.Timer | None = None

    @property
    def pid(self) -> int | None:
        """The current incarnation's pid on its host."""
        return self._pid

    def spawn(self) -> None:
        """Ask the agent to start a new incarnation; ``OSError`` if it cannot."""
        with self._lock:
            self.incarnation += 1
            self._code, self._pid = None, None
            self._done.clear()
            out_r, out_w = os.pipe()
            err_r, err_w = os.pipe()
            exit_r, exit_w = os.pipe()
            self._writers = {"stdout": out_w, "stderr": err_w}
            self._exit_w = exit_w
        try:
            self._pid = self._hosts.start(self)
        except BaseException:
            with self._lock:
                self._close_writers()
                if self._exit_w is not None:
                    os.close(self._exit_w)
                    self._exit_w = None
            for fd in (out_r, err_r, exit_r):
                os.close(fd)
            raise
        self.streams.clear()
        self.add_stream(out_r, "stdout")
        self.add_stream(err_r, "stderr")
        self.pidfd = exit_r

    # -- from the agent (Zenoh threads) ---------------------------------------------------

    def deliver(self, incarnation: int, event: dict[str, Any]) -> None:
        """An event of the agent for ``incarnation`` (older incarnations' are dropped)."""
        with self._lock:
            if incarnation != self.incarnation or self._code is not None:
                return
            if event.get("kind") == "line":
                writer = self._writers.get(str(event.get("stream")))
                if writer is not None:
                    _write(writer, f"{event.get('text', '')}\n".encode())
            elif event.get("kind") == "exit":
                self._finish(int(event.get("code", LOST)))

    def lost(self, why: str) -> None:
        """Give the current incarnation up: it counts as exited with :data:`LOST`."""
        with self._lock:
            if self._code is None and self._exit_w is not None:
                _write(self._writers["stderr"], f"[launchkit] {why}\n".encode())
                self._finish(LOST)

    def _finish(self, code: int) -> None:
        """Record the exit (under the lock): end the output, make the exit pipe readable."""
        self._code = code
        self._close_writers()
        if self._exit_w is not None:
            _write(self._exit_w, b"x")
            os.close(self._exit_w)
            self._exit_w = None
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
        self._done.set()

    def _close_writers(self) -> None:
        for fd in self._writers.values():
            with contextlib.suppress(OSError):
                os.close(fd)
        self._writers = {}

    # -- what the supervisor uses -----------------------------------------------------------

    def poll(self) -> int | None:
        """The exit status, once the agent reported it (or the process was given up)."""
        return self._code

    def signal_group(self, signum: int) -> None:
        """Have the agent send ``signum`` to the process's group; a SIGKILL not confirmed
        within :data:`KILL_WAIT` seconds gives the process up."""
        self._hosts.signal(self, signum)
        if signum == signal.SIGKILL and self._timer is None and self._code is None:
            self._timer = threading.Timer(
                KILL_WAIT,
                self.lost,
                (f"agent {self.machine} did not confirm SIGKILL within {KILL_WAIT:g} s",),
            )
            self._timer.daemon = True
            self._timer.start()

    def group_alive(self) -> bool:
        """Nothing is left behind here: the agent kills a finished process's group."""
        return False

    def kill_leftovers(self) -> None:
        """SIGKILL the process (its whole group, on its host)."""
        if self._code is None:
            self.signal_group(signal.SIGKILL)

    def reap(self) -> None:
        """Wait for the exit (a SIGKILL was sent), at most until it is given up."""
        if not self._done.wait(KILL_WAIT + 1.0):
            self.lost(f"agent {self.machine} did not report the exit")


def _write(fd: int, data: bytes) -> None:
    with contextlib.suppress(OSError):
        os.write(fd, data)
