"""The plugin host: a copy of the simulator server, made before it joins the ROS network, from
which the plugin node processes (diff drive, camera) are forked with the message layer
already imported.

A plugin node started cold pays 0.6-0.7 s of CPU (1-2 s of wall time on a busy 2-core machine)
importing numpy, rosbags, building the message types and their codecs and the node API before
it publishes anything; the server pays most of that too. So the server, once it has imported
what it needs anyway (:func:`preload`) and *before* it opens a Zenoh session (a process with
Zenoh's threads running cannot be forked safely), forks this host. The host builds what only
the plugin nodes use (:func:`warm_plugins`) while the server loads its world, opens no session,
starts no thread, and waits on a Unix socket.

Each plugin node is still a process the launcher (or, without one, the server) starts and
supervises: :mod:`plugin_trampoline` is that process. It hands the host its command line, its
environment, its working folder and its stdin/stdout/stderr; the host forks the node from
itself (in a session of its own, the trampoline's output streams as its own), reports the
node's pid, and when the node exits, its exit status; the trampoline forwards the signals it
gets to the node and ends with the node's status. A node whose trampoline dies (SIGKILL) kills
itself (:func:`_die_with`); the host exits once the server is gone and its nodes have ended.
"""

from __future__ import annotations

import array
import contextlib
import faulthandler
import importlib
import json
import os
import runpy
import select
import shutil
import signal
import socket
import sys
import tempfile
import threading
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from launchkit.envvars import RUN_TMPDIR

TRAMPOLINE = str(Path(__file__).with_name("plugin_trampoline.py"))
#: The most a request (command line and environment) may hold, in bytes.
MAX_REQUEST = 1 << 20
#: The modules of the plugin nodes, imported by the host.
PLUGIN_MODULES = (
    "launchkit.stock.gazebo_ros.diff_drive_node",
    "launchkit.stock.gazebo_ros.camera_node",
)
#: The message types the plugin nodes publish and subscribe, their codecs built by the host.
PLUGIN_MESSAGES = (
    ("nav_msgs", "Odometry"),
    ("sensor_msgs", "JointState"),
    ("tf2_msgs", "TFMessage"),
    ("geometry_msgs", "Twist"),
    ("sensor_msgs", "Image"),
    ("sensor_msgs", "CameraInfo"),
)
#: The services every node serves (:class:`launchkit.ros.parameter_service.ParameterService`).
PARAMETER_SERVICES = tuple(
    f"rcl_interfaces/srv/{name}"
    for name in (
        "ListParameters",
        "GetParameters",
        "GetParameterTypes",
        "SetParameters",
        "SetParametersAtomically",
        "DescribeParameters",
    )
)


def preload() -> None:
    """Before the fork, in the server: import and build what the server needs anyway before
    it loads its world (the node API, the message type store, the parameter services' types),
    so that the host has it without paying for it again."""
    from launchkit.ros.msgs import get_service

    importlib.import_module("launchkit.ros.node")
    for service in PARAMETER_SERVICES:
        get_service(service)


def warm_plugins() -> None:
    """After the fork, in the host (beside the server's world load): what only the plugin
    nodes use, their modules and their message types' codecs."""
    from launchkit.ros.msgs._codec import codec
    from launchkit.stock.gazebo_ros import messages

    for module in PLUGIN_MODULES:
        importlib.import_module(module)
    for package, name in PLUGIN_MESSAGES:
        codec(messages.message_class(package, name).__msgtype__)


@dataclass
class PluginHost:
    """The server's handle on its plugin host: where the host listens, and the pipe whose
    closing (the server's exit, however it happens) tells the host to finish."""

    socket_path: str
    folder: str
    pid: int
    lifeline: int

    @classmethod
    def fork(cls, log: Callable[[str], None]) -> PluginHost | None:
        """Fork the host from this process (which must not have opened a Zenoh session yet);
        None where that cannot be done (no ``pidfd_open``, no socket, no fork; ``log`` says
        why), and the nodes start cold."""
        try:
            os.close(os.pidfd_open(os.getpid()))  # Python 3.9+ on Linux 5.3+
        except (AttributeError, OSError) as error:
            log(f"no plugin host (no pidfd_open: {error}): the plugin nodes start on their own")
            return None
        base = os.environ.get(RUN_TMPDIR)
        folder = tempfile.mkdtemp(
            prefix="gazebo-host-", dir=base if base and os.path.isdir(base) else None
        )
        path = os.path.join(folder, "host.sock")
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        read_end, write_end = os.pipe()
        try:
            listener.bind(path)
            listener.listen(16)
            for stream in (sys.stdout, sys.stderr):
                stream.flush()  # or the child would write what is buffered a second time
            pid = os.fork()
        except OSError as error:
            log(f"no plugin host ({error}): the plugin nodes start on their own")
            for fd in (read_end, write_end):
                os.close(fd)
            listener.close()
            shutil.rmtree(folder, ignore_errors=True)
            return None
        if pid == 0:
            code = 1
            try:
                os.close(write_end)
                code = _Host(listener, read_end).serve()
            except BaseException:  # nothing may unwind into the server's frames
                traceback.print_exc()
            finally:
                os._exit(code)
        listener.close()
        os.close(read_end)
        return cls(path, folder, pid, write_end)

    def command(self, argv: list[str]) -> list[str]:
        """The command that runs ``argv`` (``python -m MODULE ...``) forked from the host, or
        ``argv`` itself if the host cannot be reached."""
        return [sys.executable, "-I", "-S", TRAMPOLINE, self.socket_path, *argv]

    def close(self) -> None:
        """Tell the host to finish (once its nodes have ended) and remove its folder."""
        with contextlib.suppress(OSError):
            os.close(self.lifeline)
        shutil.rmtree(self.folder, ignore_errors=True)
        with contextlib.suppress(ChildProcessError, OSError):
            os.waitpid(self.pid, os.WNOHANG)


class _Host:
    """The host's loop: accept a trampoline, fork its node, report the node's exit."""

    def __init__(self, listener: socket.socket, lifeline: int) -> None:
        self.listener: socket.socket | None = listener
        self.lifeline = lifeline
        #: node pid -> (its pidfd, the trampoline's connection)
        self.nodes: dict[int, tuple[int, socket.socket]] = {}

    def serve(self) -> int:
        os.setsid()  # out of the server's process group: its signals are not for the host
        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(signum, signal.SIG_IGN)
        try:
            warm_plugins()
        except Exception:  # the nodes then build it themselves; say why
            traceback.print_exc()
        while self.listener is not None or self.nodes:
            watched: list[int] = [fd for fd, _ in self.nodes.values()]
            if self.listener is not None:
                watched += [self.listener.fileno(), self.lifeline]
            ready, _, _ = select.select(watched, [], [])
            for node, (pidfd, _) in list(self.nodes.items()):
                if pidfd in ready:
                    self._reap(node)
            if self.listener is not None and self.lifeline in ready:
                self.listener.close()  # the server is gone: no new nodes
                self.listener = None
            elif self.listener is not None and self.listener.fileno() in ready:
                self._accept()
        return 0

    def _accept(self) -> None:
        assert self.listener is not None
        conn, _ = self.listener.accept()
        fds = array.array("i")
        try:
            data, ancillary, _, _ = conn.recvmsg(MAX_REQUEST, socket.CMSG_SPACE(3 * fds.itemsize))
            for level, kind, payload in ancillary:
                if level == socket.SOL_SOCKET and kind == socket.SCM_RIGHTS:
                    fds.frombytes(payload[: len(payload) - len(payload) % fds.itemsize])
            request = _checked(json.loads(data))
            if len(fds) != 3:
                raise ValueError(f"expected stdin, stdout and stderr, got {len(fds)} descriptors")
            trampoline = _peer_pid(conn)
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
            print(f"plugin host: cannot start a node: {error}", file=sys.stderr, flush=True)
            conn.close()
            return
        finally:
            for fd in fds:
                os.close(fd)
        self.nodes[pid] = (pidfd, conn)
        _send(conn, f"pid {pid}")

    def _reap(self, pid: int) -> None:
        pidfd, conn = self.nodes.pop(pid)
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
            for pidfd, other in self.nodes.values():
                os.close(pidfd)
                other.close()
            if self.listener is not None:
                self.listener.close()
            os.close(self.lifeline)
            # A fresh process's signal dispositions, not the server's.
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
