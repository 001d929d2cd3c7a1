"""The launcher's child-request socket: processes of a launch ask it to start processes for them.

The supervisor opens a ``SOCK_SEQPACKET`` Unix socket in its private (0700) run folder and
gives its path to every process it starts (``$LAUNCHKIT_SUPERVISOR_SOCKET``). Connections and
requests are read by the supervisor's own loop, on its thread, like everything else. The
protocol and the client are in :mod:`launchkit.runtime.supervisor_client`.

A connection belongs to the process of the launch whose session the connecting process is in
(every process the launcher starts leads its own session). Any other connection, and one beyond
:data:`MAX_CONNECTIONS`, gets one error reply at once and is closed when its first request (or
its end) arrives, and at the latest when :data:`MAX_REFUSED` newer refused ones wait: whatever
connects, the launcher holds a bounded number of descriptors for it. A
process started on request inherits its owner's launch environment, working folder, output mode
and stop timeouts unless the request says otherwise, and is supervised like a declared one.
When the connection closes (the owner exited, crashed, was restarted or closed the client)
every process it started is stopped and not respawned, so such a process never outlives its
owner nor keeps the launch alive. A bad request gets an error reply; it never stops the launch.
"""

from __future__ import annotations

import json
import math
import os
import selectors
import socket
import struct
from collections import deque
from typing import Any, Protocol

from launchkit.description.process_spec import OUTPUT_MODES, ProcessSpec
from launchkit.envvars import SUPERVISOR_SOCKET
from launchkit.runtime.lifecycle import State
from launchkit.runtime.process import SupervisedProcess
from launchkit.runtime.supervisor_client import MAX_PACKET

_START_KEYS = {"op", "name", "cmd", "env", "cwd", "respawn", "respawn_delay", "output"}
_UCRED = struct.Struct("3i")  # pid, uid, gid
#: Connections open at once; one more is refused (each process of a launch needs one).
MAX_CONNECTIONS = 256
#: Refused connections kept until their peer's request arrives (so it can read why).
MAX_REFUSED = 16


class RequestError(Exception):
    """A request that cannot be served; its message is the error reply."""


class ChildHost(Protocol):
    """What the requests need from the supervisor."""

    def owner_of(self, pid: int) -> SupervisedProcess | None:
        """The running process of the launch whose session ``pid`` is in."""

    def start_child(self, spec: ProcessSpec, owner: SupervisedProcess) -> SupervisedProcess:
        """Start ``spec`` for ``owner`` now; :class:`RequestError` if it cannot be."""

    def stop_child(self, process: SupervisedProcess) -> None:
        """Stop ``process`` (SIGINT, then escalation) and never respawn it."""

    def log(self, level: str, logger: str, message: str) -> None:
        """A launch line."""

    def announce(self, logger: str, text: str) -> None:
        """A line for the user under ``logger``, printed once the launch's console settles."""


class _Connection:
    def __init__(self, sock: socket.socket, owner: SupervisedProcess, peer: int) -> None:
        self.sock = sock
        self.owner = owner
        self.peer = peer
        self.started: dict[int, SupervisedProcess] = {}


class ChildRequests:
    """The listening socket, its connections, and what each connection started."""

    def __init__(self, host: ChildHost, selector: selectors.BaseSelector, folder: str) -> None:
        """Listen in ``folder`` (private to the launcher); ``OSError`` where Unix seqpacket
        sockets are missing."""
        self._host = host
        self._selector = selector
        if not hasattr(socket, "SO_PEERCRED"):
            raise OSError("this system cannot tell who connects to a Unix socket (SO_PEERCRED)")
        self.path = os.path.join(folder, "children.sock")
        self._listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            self._listener.bind(self.path)
            self._listener.listen(16)
        except OSError:
            self._listener.close()
            raise
        self._listener.setblocking(False)
        self._connections: dict[int, _Connection] = {}
        self._refused: deque[socket.socket] = deque()
        selector.register(self._listener, selectors.EVENT_READ, self._accept)

    def environment(self) -> dict[str, str]:
        """What a process needs in its environment to make requests."""
        return {SUPERVISOR_SOCKET: self.path}

    def close(self) -> None:
        """Close every connection and the socket (its folder is the supervisor's to remove)."""
        for connection in list(self._connections.values()):
            self._forget(connection)
        while self._refused:
            self._drop_refused(self._refused[0])
        self._selector.unregister(self._listener)
        self._listener.close()
        try:
            os.unlink(self.path)
        except OSError:
            pass

    # -- on the supervisor's loop ------------------------------------------------------------

    def _accept(self) -> None:
        try:
            sock, _ = self._listener.accept()
        except OSError:  # nothing to accept after all, or the peer gave up already
            return
        sock.setblocking(False)
        pid = 0
        try:
            credentials = sock.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, _UCRED.size)
            pid = _UCRED.unpack(credentials)[0]
            owner = self._host.owner_of(os.getsid(pid))
        except OSError:
            owner = None  # it is gone already
        if owner is None:
            self._refuse(sock, f"process {pid} is not a process of this launch")
            return
        if len(self._connections) >= MAX_CONNECTIONS:
            self._refuse(sock, f"the launcher has {MAX_CONNECTIONS} connections open already")
            return
        connection = _Connection(sock, owner, pid)
        self._connections[sock.fileno()] = connection
        self._selector.register(sock, selectors.EVENT_READ, lambda: self._receive(connection))

    def _refuse(self, sock: socket.socket, reason: str) -> None:
        """Send the error reply the peer's first request will read; close the connection once
        that request arrives (closing earlier would reset it and lose the reply)."""
        try:
            sock.send(json.dumps({"ok": False, "error": reason}).encode())
        except OSError:
            sock.close()
            return
        if len(self._refused) >= MAX_REFUSED:
            self._drop_refused(self._refused[0])
        self._refused.append(sock)
        self._selector.register(sock, selectors.EVENT_READ, lambda: self._drop_refused(sock))

    def _drop_refused(self, sock: socket.socket) -> None:
        self._refused.remove(sock)
        self._selector.unregister(sock)
        # read what it sent first: closing a socket with unread data resets the peer, which
        # then cannot read the reply
        for _ in range(8):
            try:
                if not sock.recv(MAX_PACKET):
                    break
            except OSError:
                break
        sock.close()

    def _receive(self, connection: _Connection) -> None:
        try:
            data, _, flags, _ = connection.sock.recvmsg(MAX_PACKET)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            data, flags = b"", 0
        if not data:
            self._closed(connection)
            return
        try:
            if flags & socket.MSG_TRUNC:
                raise RequestError(f"request too long (at most {MAX_PACKET} bytes)")
            reply = {"ok": True, **self._serve(connection, _parse(data))}
        except RequestError as error:
            reply = {"ok": False, "error": str(error)}
        except Exception as error:  # a request must never take the launch down
            self._host.log("WARNING", "launch", f"child request failed: {error!r}")
            reply = {"ok": False, "error": f"internal error: {error!r}"}
        try:
            connection.sock.send(json.dumps(reply).encode())
        except OSError:
            # it does not read its replies (or is gone): treat it as closed
            self._closed(connection)

    def _serve(self, connection: _Connection, request: dict[str, Any]) -> dict[str, Any]:
        owner = connection.owner
        op = request.get("op")
        if op == "start":
            process = self._host.start_child(_spec(request, owner), owner)
            connection.started[process.index] = process
            return {"id": process.index, "pid": process.pid, "label": process.label}
        if op == "stop":
            process_id = request.get("id")
            if set(request) != {"op", "id"} or type(process_id) is not int:
                raise RequestError('a stop request is {"op": "stop", "id": ID}')
            stopped = connection.started.get(process_id)
            if stopped is None:
                raise RequestError(f"no process {process_id} was started by this connection")
            self._host.stop_child(stopped)
            return {}
        if op == "announce":
            text = request.get("text")
            if set(request) != {"op", "text"} or not isinstance(text, str):
                raise RequestError('an announce request is {"op": "announce", "text": TEXT}')
            if not text or len(text) > 500 or not text.isprintable():
                raise RequestError("text must be one printable line of at most 500 characters")
            self._host.announce(owner.label, text)
            return {}
        raise RequestError(f"unknown op {op!r} (expected 'start', 'stop' or 'announce')")

    def _closed(self, connection: _Connection) -> None:
        self._forget(connection)
        running = [
            p
            for p in connection.started.values()
            if not p.lifecycle.retired and (p.alive or p.state is State.BACKOFF)
        ]
        if running:
            self._host.log(
                "INFO",
                "launch",
                f"{connection.owner.label} closed its child-request connection: stopping "
                + ", ".join(p.label for p in running),
            )
        for process in running:
            self._host.stop_child(process)

    def _forget(self, connection: _Connection) -> None:
        if self._connections.pop(connection.sock.fileno(), None) is not None:
            self._selector.unregister(connection.sock)
        connection.sock.close()


def _parse(data: bytes) -> dict[str, Any]:
    try:
        request = json.loads(data)
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise RequestError(f"not JSON: {error}") from None
    if not isinstance(request, dict):
        raise RequestError("a request is a JSON object")
    return request


def _spec(request: dict[str, Any], owner: SupervisedProcess) -> ProcessSpec:
    """The process a start request asks for, with its owner's settings as defaults."""
    unknown = set(request) - _START_KEYS
    if unknown:
        raise RequestError(f"unknown field(s) {', '.join(sorted(unknown))} in a start request")
    name = request.get("name")
    if not isinstance(name, str) or not name or any(c == "/" or not c.isprintable() for c in name):
        raise RequestError("name must be a non-empty string without '/' or control characters")
    cmd = request.get("cmd")
    if not isinstance(cmd, list) or not cmd or not all(isinstance(w, str) for w in cmd):
        raise RequestError("cmd must be a non-empty list of strings (the argv)")
    if any("\0" in word for word in cmd):
        raise RequestError("cmd must not contain NUL characters")
    env = request.get("env", {})
    if not isinstance(env, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in env.items()
    ):
        raise RequestError("env must map strings to strings")
    if any("\0" in k or "=" in k or not k or "\0" in v for k, v in env.items()):
        raise RequestError("env names must be non-empty, without '=' or NUL; values without NUL")
    cwd = request.get("cwd", owner.spec.cwd)
    if cwd is not None and (not isinstance(cwd, str) or "\0" in cwd):
        raise RequestError("cwd must be a string (without NUL)")
    respawn = request.get("respawn", False)
    if not isinstance(respawn, bool):
        raise RequestError("respawn must be true or false")
    delay = request.get("respawn_delay", 0.0)
    if type(delay) not in (int, float) or not math.isfinite(delay) or delay < 0:
        raise RequestError("respawn_delay must be a number of seconds >= 0")
    output = request.get("output", owner.spec.output)
    if output not in OUTPUT_MODES:
        raise RequestError(f"output must be one of {', '.join(OUTPUT_MODES)}")
    return ProcessSpec(
        name=name,
        cmd=list(cmd),
        env={**owner.spec.env, **env},
        cwd=cwd,
        output=output,
        sigterm_timeout=owner.spec.sigterm_timeout,
        sigkill_timeout=owner.spec.sigkill_timeout,
        respawn=respawn,
        respawn_delay=float(delay),
    )
