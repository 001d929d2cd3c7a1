"""The event channel from a launcher to a test process (``launchkit run --events-fd FD``).

The launcher writes one JSON object a line on a Unix stream socket it inherited as ``FD``::

    {"event": "started", "process": "talker-1", "name": "talker", "node": "chatter",
     "pid": 4242, "cmd": [...], "respawn": false, "required": false, "sigterm_timeout": 5.0,
     "sigkill_timeout": 5.0}                    required: on_exit="shutdown"
    {"event": "output", "process": "talker-1", "stream": "stdout", "text": "hello 1"}
    {"event": "stopping", "process": "worker-4"}  one process stopped on request (not a shutdown)
    {"event": "exited", "process": "talker-1", "pid": 4242, "returncode": 0}
    {"event": "ready"}                          the first pass is done
    {"event": "failed", "message": "f.xml:3:5: error: ..."}   before ready; the launcher exits 2
    {"event": "error", "message": "..."}        while running; shutdown follows (but for a
                                                process that could not start in a missing folder)
    {"event": "shutdown", "reason": "..."}

The socket is also a lifeline: when the test process goes away (its end closes), the launcher
sends itself SIGTERM and so shuts down as it would on a ``kill``, leaving nothing behind.
"""

from __future__ import annotations

import itertools
import json
import os
import signal
import socket
import threading
from typing import TYPE_CHECKING, Any

from launchkit.runtime.hooks import SupervisorHooks

if TYPE_CHECKING:
    from launchkit.runtime.process import SupervisedProcess


class EventWriter(SupervisorHooks):
    """Writes the launch's events as JSON lines; the launcher end of the channel."""

    def __init__(self, channel: socket.socket) -> None:
        self._channel = channel
        self._lock = threading.Lock()
        self._closing = False
        self._broken = False
        watcher = threading.Thread(target=self._watch_peer, name="launchkit-events", daemon=True)
        watcher.start()

    @classmethod
    def from_fd(cls, fd: int) -> EventWriter:
        """The writer for an inherited socket file descriptor."""
        channel = socket.socket(fileno=fd)
        channel.set_inheritable(False)  # children must not hold the lifeline open
        return cls(channel)

    def launch_ready(self) -> None:
        """See :class:`SupervisorHooks`."""
        self._send({"event": "ready"})

    def launch_failed(self, message: str) -> None:
        """The launch failed before it was ready (the launcher's error message)."""
        self._send({"event": "failed", "message": message})

    def launch_error(self, message: str) -> None:
        """See :class:`SupervisorHooks`."""
        self._send({"event": "error", "message": message})

    def process_started(self, process: SupervisedProcess) -> None:
        """See :class:`SupervisorHooks`."""
        spec = process.spec
        self._send(
            {
                "event": "started",
                "process": process.label,
                "name": spec.name,
                "node": node_name(spec.cmd),
                "pid": process.pid,
                "cmd": spec.cmd,
                "respawn": spec.respawn,
                "required": spec.on_exit_shutdown,
                "sigterm_timeout": spec.sigterm_timeout,
                "sigkill_timeout": spec.sigkill_timeout,
            }
        )

    def process_output(self, process: SupervisedProcess, stream: str, line: str) -> None:
        """See :class:`SupervisorHooks`."""
        self._send({"event": "output", "process": process.label, "stream": stream, "text": line})

    def process_stopping(self, process: SupervisedProcess) -> None:
        """See :class:`SupervisorHooks`."""
        self._send({"event": "stopping", "process": process.label})

    def process_exited(self, process: SupervisedProcess, returncode: int) -> None:
        """See :class:`SupervisorHooks`."""
        self._send(
            {
                "event": "exited",
                "process": process.label,
                "pid": process.pid,
                "returncode": returncode,
            }
        )

    def shutdown(self, reason: str) -> None:
        """See :class:`SupervisorHooks`."""
        self._send({"event": "shutdown", "reason": reason})

    def close(self) -> None:
        """Close the channel (the launcher is about to exit on its own)."""
        self._closing = True
        try:
            self._channel.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        self._channel.close()

    def _send(self, event: dict[str, Any]) -> None:
        if self._broken:
            return
        data = (json.dumps(event) + "\n").encode()
        with self._lock:
            try:
                self._channel.sendall(data)
            except OSError:
                self._broken = True  # the test process is gone; the watcher stops the launch

    def _watch_peer(self) -> None:
        try:
            while self._channel.recv(4096):
                pass
        except OSError:
            pass
        if not self._closing:
            os.kill(os.getpid(), signal.SIGTERM)


def node_name(cmd: list[str]) -> str | None:
    """The ROS node name a command line sets with ``-r __node:=NAME``, if any."""
    for flag, value in itertools.pairwise(cmd):
        if flag in ("-r", "--remap") and value.startswith("__node:="):
            return value.split(":=", 1)[1]
    return None
