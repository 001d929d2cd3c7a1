"""The launcher's node host: one pre-imported process from which the stock Python nodes of a
launch (the simulator server, ``spawn_entity.py``, ``robot_state_publisher``) are forked,
instead of each starting a cold interpreter and importing numpy, rosbags, zenoh and the ROS
layer again (0.5-0.6 s of CPU each).

The host is started as soon as the launch says it will run such a node (in the first pass,
while the launcher is still evaluating the rest of the file), imports the shared layer and the
nodes' modules, then forks a node for each trampoline (:mod:`launchkit.runtime.fork_trampoline`)
that asks. The launcher supervises the trampoline as it supervised the node: pid, process
group, output streams, signals, exit status, respawn (:mod:`launchkit.runtime.fork_host`).

The launcher makes the listening socket itself and hands it to the host, so a trampoline that
starts before the host has finished importing waits in the socket's queue. The host is in its
own session, watched by the orphan guard and killed with the launcher (``PR_SET_PDEATHSIG``);
its nodes die with their trampolines. A host that cannot be made, or that died, costs one log
line: the nodes start cold, as before.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.process_spec import ProcessSpec

if TYPE_CHECKING:  # imported when a launch runs a hosted node: not by an empty launch
    import subprocess

#: The stock node modules forked from the host.
HOSTED = frozenset(
    {
        "launchkit.stock.gazebo_ros.server",
        "launchkit.stock.gazebo_ros.spawn_entity",
        "launchkit.stock.robot_state_publisher.node",
    }
)
#: The host's program (run as ``python -m``; it imports the ROS layer, which this layer may not).
HOST_MODULE = "launchkit.stock._node_host"
#: How long the launcher waits for the host to say which trampoline stands for a node.
OWNER_TIMEOUT = 5.0


def hosted_module(spec: ProcessSpec) -> str | None:
    """The stock module ``spec`` runs, if it is one to fork from the host."""
    cmd = spec.cmd
    if spec.machine or spec.emulate_tty or len(cmd) < 3:
        return None
    if cmd[0] != sys.executable or cmd[1] != "-m" or cmd[2] not in HOSTED:
        return None
    return cmd[2]


class NodeHost:
    """The launch's node host, started at the first stock node it will run."""

    def __init__(
        self,
        log: Callable[[str, str, str], None],
        folder: Callable[[], Path],
        watch: Callable[[int], None],
        forget: Callable[[int], None],
    ) -> None:
        self._log = log
        self._folder = folder
        self._watch = watch
        self._forget = forget
        self._process: subprocess.Popen[bytes] | None = None
        self._path = ""
        self._tried = False

    def expect(self, spec: ProcessSpec) -> None:
        """The launch will run ``spec``: start the host now if it is the first hosted node."""
        if self._tried or hosted_module(spec) is None:
            return
        self._tried = True
        import socket
        import subprocess

        listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            path = str(self._folder() / "node-host.sock")
            listener.bind(path)
            listener.listen(32)
            env = dict(os.environ, OPENBLAS_NUM_THREADS="1")  # no BLAS threads: safe to fork
            modules = sorted(HOSTED)
            fd = str(listener.fileno())
            self._process = subprocess.Popen(
                [sys.executable, "-m", HOST_MODULE, fd, str(os.getpid()), *modules],
                env=env,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,  # not a terminal: a forked node buffers as a cold one
                pass_fds=(listener.fileno(),),
                start_new_session=True,
            )
        except OSError as error:
            self._log("WARNING", "launch", f"no node host ({error}): stock nodes start cold")
            return
        finally:
            listener.close()  # the host's copy is the only one: its end refuses trampolines
        self._path = path
        self._watch(self._process.pid)

    def command(self, cmd: list[str], spec: ProcessSpec) -> list[str]:
        """What to run for ``spec``: its trampoline if the host forks it, else ``cmd``."""
        if self._process is None or hosted_module(spec) is None:
            return cmd
        code = self._process.poll()
        if code is not None:
            self._log(
                "WARNING",
                "launch",
                f"node host exited ({code}): stock nodes start cold from now on",
            )
            self._forget(self._process.pid)
            self._process = None
            return cmd
        from launchkit.runtime.fork_host import trampoline_command

        return trampoline_command(self._path, cmd)

    def trampoline_of(self, pid: int) -> int | None:
        """The pid of the trampoline that stands for node ``pid`` (None: not the host's)."""
        if self._process is None or self._process.poll() is not None:
            return None
        import json
        import socket

        try:
            with socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET) as conn:
                conn.settimeout(OWNER_TIMEOUT)
                conn.connect(self._path)
                conn.send(json.dumps({"owner": pid}).encode())
                reply = conn.recv(256).decode().split()
        except OSError:
            return None
        if len(reply) == 2 and reply[0] == "trampoline" and reply[1].isdigit():
            return int(reply[1])
        return None

    def close(self) -> None:
        """The launch is over (its nodes have ended): end the host."""
        process, self._process = self._process, None
        if process is None:
            return
        with contextlib.suppress(OSError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        self._forget(process.pid)
