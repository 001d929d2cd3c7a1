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
supervises: a trampoline (:mod:`launchkit.runtime.fork_trampoline`) that has the host fork
the node, as :mod:`launchkit.runtime.fork_host` describes; the host exits once the server is
gone and its nodes have ended.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import shutil
import socket
import sys
import tempfile
import traceback
from collections.abc import Callable
from dataclasses import dataclass

from launchkit.envvars import RUN_TMPDIR
from launchkit.runtime.fork_host import ForkHost, trampoline_command

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


def warm_plugins() -> None:
    """After the fork, in the host (beside the server's world load): what only the plugin
    nodes use, their modules and their message types' codecs."""
    from launchkit.ros.msgs import codec
    from launchkit.stock.gazebo_ros import messages

    for module in PLUGIN_MODULES:
        importlib.import_module(module)
    for package, name in PLUGIN_MESSAGES:
        codec(messages.message_class(package, name)._TYPE_NAME)


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
                code = ForkHost(listener, read_end, warm_plugins).serve()
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
        return trampoline_command(self.socket_path, argv)

    def close(self) -> None:
        """Tell the host to finish (once its nodes have ended) and remove its folder."""
        with contextlib.suppress(OSError):
            os.close(self.lifeline)
        shutil.rmtree(self.folder, ignore_errors=True)
        with contextlib.suppress(ChildProcessError, OSError):
            os.waitpid(self.pid, os.WNOHANG)
