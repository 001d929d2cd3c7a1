"""A fork host: a pre-imported Python process, with no thread and no network session, that
forks ``python -m MODULE ...`` nodes from itself at a trampoline's request.

A node started cold pays the interpreter and its imports (numpy, rosbags, zenoh, the message
layer: 0.5-0.7 s of CPU) before it does anything. A host pays them once, then forks each node
with them imported. Two hosts use this loop: the simulator server's plugin host
(:mod:`launchkit.stock.gazebo_ros.plugin_host`) and the launcher's node host
(:mod:`launchkit.runtime.node_host`).

Each node is still a process its supervisor starts: :mod:`fork_trampoline` is that process. It
hands the host its command line, its environment, its working folder and its stdin/stdout/
stderr; the host forks the node from itself (in a session of its own, the trampoline's output
streams as its own), reports the node's pid, and when the node exits, its exit status; the
trampoline forwards the signals it gets to the node and ends with the node's status. A node
whose trampoline dies (SIGKILL) kills itself (:func:`_die_with`). A request the host cannot
serve gets no pid: its trampoline then runs the command itself (cold).

Its supervisor may also ask which trampoline stands for a node (``{"owner": PID}``): a node's
session is its own, not its trampoline's.
"""

from __future__ import annotations

import array
import contextlib
import faulthandler
import json
import os
import runpy
import select
import signal
import socket
import sys
import threading
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

#: The standard-library process that stands for a forked node.
TRAMPOLINE = str(Path(__file__).with_name("fork_trampoline.py"))
#: The most a request (command line and environment) may hold, in bytes.
MAX_REQUEST = 1 << 20


def trampoline_command(socket_path: str, argv: list[str]) -> list[str]:
    """The command that runs ``argv`` (``python -m MODULE ...``) forked from the host at
    ``socket_path`` (or, if the host cannot serve it, ``argv`` itself)."""
    return [sys.executable, "-I", "-S", TRAMPOLINE, socket_path, *argv]


class ForkHost:
    """The host's loop: accept a trampoline, fork its node, report the node's exit.

    ``lifeline``: a pipe whose end (its writer gone) stops the accepting; the host then exits
    once its nodes have ended (None: it serves until killed). ``same_env``: prefixes of the
    environment variables a request must have exactly as this process has them (the
    interpreter's settings, ``PYTHON*``: a node that needs others starts cold)."""

    def __init__(
        self,
        listener: socket.socket,
        lifeline: int | None,
        warm: Callable[[], None],
        same_env: tuple[str, ...] = (),
    ) -> None:
        self.listener: socket.socket | None = listener
        self.lifeline = lifeline
        self.warm = warm
        self.same_env = _matching(dict(os.environ), same_env)
        self.same_prefixes = same_env
        #: node pid -> (its pidfd, the trampoline's connection, the trampoline's pid)
        self.nodes: dict[int, tuple[int, socket.socket, int]] = {}

    def serve(self) -> int:
        """Warm up, then serve until the lifeline ends and the nodes have ended."""
        with contextlib.suppress(OSError):  # started as a session leader already
            os.setsid()  # out of the parent's process group: its signals are not for the host
        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(signum, signal.SIG_IGN)
        try:
            self.warm()
        except Exception:  # the nodes then build it themselves; say why
            traceback.print_exc()
        while self.listener is not None or self.nodes:
            watched: list[int] = [fd for fd, _, _ in self.nodes.values()]
            if self.listener is not None:
                watched.append(self.listener.fileno())
                if self.lifeline is not None:
                    watched.append(self.lifeline)
            ready, _, _ = select.select(watched, [], [])
            for node, (pidfd, _, _) in list(self.nodes.items()):
                if pidfd in ready:
                    self._reap(node)
            if self.listener is not None and self.lifeline in ready:
                self.listener.close()  # the parent is gone: no new nodes
                self.listener = None
            elif self.listener is not None and self.listener.fileno() in ready:
                self._accept()
        return 0

    def _accept(self) -> None:
        assert self.listener is not None
        try:
            conn, _ = self.listener.accept()
        except OSError:
            return  # the peer gave up already
        fds = array.array("i")
        try:
            data, ancillary, _, _ = conn.recvmsg(MAX_REQUEST, socket.CMSG_SPACE(3 * fds.itemsize))
            for level, kind, payload in ancillary:
                if level == socket.SOL_SOCKET and kind == socket.SCM_RIGHTS:
                    fds.frombytes(payload[: len(payload) - len(payload) % fds.itemsize])
            request = json.loads(data)
            if isinstance(request, dict) and set(request) == {"owner"} and not fds:
                self._answer_owner(conn, request["owner"])
                return
            request = _checked(request)
            settings = _matching(request["env"], self.same_prefixes)
            if self.same_prefixes and settings != self.same_env:
                raise ValueError("its interpreter settings differ from the host's")
            if len(fds) != 3:
                raise ValueError(f"expected stdin, stdout and stderr, got {len(fds)} descriptors")
            trampoline = _peer_pid(conn)
            for stream in (sys.stdout, sys.stderr):
                stream.flush()  # or the child would write what is buffered a second time
            pid = os.fork()
            if pid == 0:
                self._become_node(request, list(fds), trampoline, conn)
            try:
                pidfd = os.pidfd_open(pid)
            except OSError:
                os.kill(pid, signal.SIGKILL)  # unwatched, it must not run beside a cold one
                os.waitpid(pid, 0)
                raise
        except (OSError, ValueError) as error:
            print(f"fork host: cannot start a node: {error}", file=sys.stderr, flush=True)
            conn.close()
            return
        finally:
            for fd in fds:
                os.close(fd)
        self.nodes[pid] = (pidfd, conn, trampoline)
        _send(conn, f"pid {pid}")

    def _answer_owner(self, conn: socket.socket, pid: Any) -> None:
        entry = self.nodes.get(pid) if type(pid) is int else None
        _send(conn, f"trampoline {entry[2]}" if entry is not None else "none")
        conn.close()

    def _reap(self, pid: int) -> None:
        pidfd, conn, _ = self.nodes.pop(pid)
        os.close(pidfd)
        _, status = os.waitpid(pid, 0)
        _send(conn, f"exit {os.waitstatus_to_exitcode(status)}")
        conn.close()

    def _become_node(
        self, request: dict[str, Any], fds: list[int], trampoline: int, conn: socket.socket
    ) -> None:
        """In the forked child: become the node the trampoline asked for; never returns."""
        code = 1
        try:
            os.setsid()
            for target, fd in enumerate(fds[:3]):
                os.dup2(fd, target)
            for fd in fds:
                os.close(fd)
            conn.close()
            for pidfd, other, _ in self.nodes.values():
                os.close(pidfd)
                other.close()
            if self.listener is not None:
                self.listener.close()
            if self.lifeline is not None:
                os.close(self.lifeline)
            # A fresh process's signal dispositions, not the host's.
            faulthandler.unregister(signal.SIGUSR1)
            faulthandler.cancel_dump_traceback_later()
            signal.signal(signal.SIGINT, signal.default_int_handler)
            for signum in (signal.SIGTERM, signal.SIGHUP, signal.SIGUSR1):
                signal.signal(signum, signal.SIG_DFL)
            _die_with(trampoline)
            os.chdir(request["cwd"])
            os.environ.clear()
            os.environ.update(request["env"])
            argv = request["argv"]
            sys.argv = [argv[2], *argv[3:]]
            if sys.path and not getattr(sys.flags, "safe_path", False):
                sys.path[0] = os.getcwd()  # as `python -m` in this folder would have it
            # As `python -m` does: the module runs as __main__ only (the host imported it
            # under its name; runpy warns about that copy).
            sys.modules.pop(argv[2], None)
            runpy.run_module(argv[2], run_name="__main__", alter_sys=True)
            code = 0
        except SystemExit as done:
            code = done.code if isinstance(done.code, int) else (0 if done.code is None else 1)
        except BaseException:  # a node's crash must not unwind into the host
            traceback.print_exc()
        finally:
            for stream in (sys.stdout, sys.stderr):
                with contextlib.suppress(OSError, ValueError):
                    stream.flush()
            os._exit(code)


def _matching(env: dict[str, str], prefixes: tuple[str, ...]) -> dict[str, str]:
    return {k: v for k, v in env.items() if prefixes and k.startswith(prefixes)}


def _checked(request: Any) -> dict[str, Any]:
    """``request`` if it is what a trampoline sends (else ValueError: no node is forked, and
    the trampoline starts its command itself)."""
    if not isinstance(request, dict):
        raise ValueError("expected a JSON object")
    argv, env, cwd = request.get("argv"), request.get("env"), request.get("cwd")
    if not (
        isinstance(cwd, str)
        and isinstance(env, dict)
        and all(isinstance(v, str) for v in env.values())
        and isinstance(argv, list)
        and all(isinstance(a, str) for a in argv)
        and len(argv) >= 3
        and argv[0] == sys.executable
        and argv[1] == "-m"
    ):
        raise ValueError("expected cwd, env and argv 'python -m MODULE ...'")
    return request


def _die_with(pid: int) -> None:
    """Kill this process's group when process ``pid`` (its trampoline) ends: a SIGKILLed
    trampoline must not leave its node behind."""
    try:
        pidfd = os.pidfd_open(pid)
    except OSError:
        os._exit(1)  # it is gone already

    def watch() -> None:
        select.select([pidfd], [], [])
        os.killpg(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, name="trampoline-watch", daemon=True).start()


def _peer_pid(conn: socket.socket) -> int:
    """The pid of the process at the other end of a Unix socket."""
    creds = conn.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, 12)
    return int(array.array("i", creds)[0])


def _send(conn: socket.socket, text: str) -> None:
    with contextlib.suppress(OSError):  # the trampoline is gone: nobody to tell
        conn.send(text.encode())
