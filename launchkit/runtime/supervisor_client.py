"""A child's end of the launcher's child-request socket: ask the ``launchkit run`` that started
this process to start (and stop) processes for it, supervised like every process of the launch.

``launchkit run`` puts the socket's path in ``$LAUNCHKIT_SUPERVISOR_SOCKET`` of every process it
starts. A process started on request gets its own ``[name-N]`` prefix, log files, respawn,
ordered stop and the orphan guard; the launcher stops it when the connection that asked for it
closes (its owner exited, crashed or closed the client). Only the standard library is used, so
any child can import this cheaply::

    client = SupervisorClient.from_environment()  # None: not started by `launchkit run`
    if client is not None:
        child = client.start("worker", [sys.executable, "worker.py"], respawn=True)
        client.stop(child.id)
        client.close()

The protocol (the server is :mod:`launchkit.runtime.child_requests`): a ``SOCK_SEQPACKET`` Unix
socket, one JSON object per packet, one reply per request, in order::

    {"op": "start", "name": "worker", "cmd": ["python3", "worker.py"], "env": {"K": "V"},
     "cwd": "/tmp", "respawn": true, "respawn_delay": 1.0, "output": "screen"}
                                    -> {"ok": true, "id": 4, "pid": 4242, "label": "worker-4"}
    {"op": "stop", "id": 4}         -> {"ok": true}
    {"op": "announce", "text": "viewer: http://127.0.0.1:8765/"}
                                    -> {"ok": true}  (printed on the launcher's console as
                                       "[INFO] [rviz2-4]: viewer: ...", whatever the output mode)
    anything wrong                  -> {"ok": false, "error": "what was wrong"}
"""

from __future__ import annotations

import json
import os
import socket
import threading
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from launchkit.envvars import SUPERVISOR_SOCKET

MAX_PACKET = 65536
DEFAULT_TIMEOUT = 5.0


class SupervisorError(Exception):
    """The launcher refused a request (its reason is the message) or the connection failed."""


@dataclass(frozen=True)
class StartedProcess:
    """A process the launcher started on request: its id (for :meth:`SupervisorClient.stop`),
    its first pid and the label its output lines are prefixed with."""

    id: int
    pid: int
    label: str


class SupervisorClient:
    """A connection to the launcher's child-request socket; requests are serialised."""

    def __init__(self, path: str, timeout: float = DEFAULT_TIMEOUT) -> None:
        self.path = path
        self._socket = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self._socket.settimeout(timeout)
        try:
            self._socket.connect(path)
        except OSError:
            self._socket.close()
            raise
        self._lock = threading.Lock()

    @classmethod
    def from_environment(
        cls, environ: Mapping[str, str] | None = None, timeout: float = DEFAULT_TIMEOUT
    ) -> SupervisorClient | None:
        """A client for ``$LAUNCHKIT_SUPERVISOR_SOCKET``; None when it is not set. Raises
        ``OSError`` when it is set but the launcher cannot be reached."""
        path = (os.environ if environ is None else environ).get(SUPERVISOR_SOCKET)
        return cls(path, timeout) if path else None

    def start(
        self,
        name: str,
        cmd: list[str],
        *,
        env: Mapping[str, str] | None = None,
        cwd: str | None = None,
        respawn: bool = False,
        respawn_delay: float = 0.0,
        output: str | None = None,
    ) -> StartedProcess:
        """Have the launcher start ``cmd`` as process ``name``. It runs with this process's
        launch environment plus ``env``; ``output`` defaults to this process's output mode."""
        request: dict[str, Any] = {
            "op": "start",
            "name": name,
            "cmd": list(cmd),
            "respawn": respawn,
            "respawn_delay": respawn_delay,
        }
        if env:
            request["env"] = dict(env)
        if cwd is not None:
            request["cwd"] = cwd
        if output is not None:
            request["output"] = output
        reply = self.request(request)
        return StartedProcess(int(reply["id"]), int(reply["pid"]), str(reply["label"]))

    def stop(self, process_id: int) -> None:
        """Have the launcher stop a process this connection started (SIGINT, then escalation);
        it is not respawned."""
        self.request({"op": "stop", "id": process_id})

    def announce(self, text: str) -> None:
        """Have the launcher print one line for the user, as its own ``[INFO]`` line under
        this process's label, on its console and in ``launch.log`` whatever this process's
        output mode (an address to open, say)."""
        self.request({"op": "announce", "text": text})

    def request(self, message: dict[str, Any]) -> dict[str, Any]:
        """Send one request and return its reply; :class:`SupervisorError` if refused or lost."""
        data = json.dumps(message).encode()
        with self._lock:
            try:
                self._socket.sendall(data)
                answer = self._socket.recv(MAX_PACKET)
            except OSError as error:
                # a launcher that refuses a connection says why, then closes it
                answer = self._refusal()
                if not answer:
                    raise SupervisorError(f"lost the launcher at {self.path}: {error}") from error
        if not answer:
            raise SupervisorError(f"the launcher at {self.path} closed the connection")
        reply = json.loads(answer)
        if not isinstance(reply, dict) or not reply.get("ok"):
            reason = reply.get("error") if isinstance(reply, dict) else reply
            raise SupervisorError(str(reason))
        return reply

    def _refusal(self) -> bytes:
        try:
            return self._socket.recv(MAX_PACKET, socket.MSG_DONTWAIT)
        except OSError:
            return b""

    def close(self) -> None:
        """Close the connection: the launcher stops what it started for it."""
        self._socket.close()

    def __enter__(self) -> SupervisorClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
