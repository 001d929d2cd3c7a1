"""The robot's plugin nodes are forked from the simulator's pre-imported plugin host
(launchkit/stock/gazebo_ros/plugin_host.py), not started as fresh interpreters, and stay
processes of the launch: the launcher's process for the diff drive is its trampoline, which
shares its output streams with the node, mirrors its exit, and takes it along when killed."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from launchkit.testing import in_order
from launchkit.testing._deadline import Deadline, scaled

DRIVING = "driving 'my_robot'"  # the diff drive's first log line


def _stat(pid: int) -> tuple[int, int]:
    """(parent pid, session id) of ``pid``."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return int(fields[1]), int(fields[3])


def _children(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if _stat(int(entry.name))[0] == pid:
                    found.append(int(entry.name))
            except (FileNotFoundError, ProcessLookupError):
                continue
    return found


def _cmdline(pid: int) -> list[str]:
    return Path(f"/proc/{pid}/cmdline").read_text().split("\0")[:-1]


def _stdout(pid: int) -> str:
    return os.readlink(f"/proc/{pid}/fd/1")


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def _node_of(trampoline: int, host: int) -> int:
    """The host's child writing to the trampoline's stdout: the node it stands for."""
    deadline = Deadline(30)
    while not deadline.expired():
        for child in _children(host):
            try:
                if _stdout(child) == _stdout(trampoline):
                    return child
            except FileNotFoundError:
                continue
        time.sleep(0.05)
    raise AssertionError(f"no child of the plugin host {host} writes to {trampoline}'s stdout")


def _wait_gone(pid: int) -> None:
    deadline = Deadline(20)
    while _alive(pid):
        if deadline.expired():
            os.kill(pid, signal.SIGKILL)
            raise AssertionError(f"process {pid} outlived its trampoline (killed now)")
        time.sleep(0.02)


def _server_node(pid: int) -> int:
    """The simulator server behind the launcher's process ``pid``: itself, or, when that is a
    trampoline, the node forked from the launcher's node host that writes to its stdout."""
    if not any(arg.endswith("fork_trampoline.py") for arg in _cmdline(pid)):
        return pid
    for entry in Path("/proc").iterdir():
        try:
            if not entry.name.isdigit() or int(entry.name) == pid:
                continue
            node, host = int(entry.name), _stat(int(entry.name))[0]
            if (
                "launchkit.stock._node_host" in _cmdline(node)
                and _cmdline(_stat(host)[0]) != _cmdline(host)  # the host's child, not a fork's
                and _stdout(node) == _stdout(pid)
            ):
                return node
        except (FileNotFoundError, ProcessLookupError):
            continue
    raise AssertionError(f"no node behind the trampoline {pid}")


def test_the_diff_drive_is_forked_from_the_pre_imported_server(launch: Any) -> None:
    handle = launch("robot_wheel", "gazebo_and_rviz.launch.xml", args={"start_rviz": False})
    controller = handle.process("gazebo_base_controller")
    controller.wait_output(DRIVING, 30)
    # The server itself is forked from the launcher's node host (tests/engine/test_node_host.py).
    server = _server_node(handle.process("gzserver").pid)
    # The host: the server's forked copy (same command line, no exec), in a session of its own.
    hosts = [c for c in _children(server) if _cmdline(c) == _cmdline(server)]
    assert len(hosts) == 1, f"expected one plugin host under gzserver {server}: {hosts}"
    host = hosts[0]
    assert _stat(host)[1] == host
    # One thread (no Zenoh session, no BLAS pool): forking it is safe.
    assert len(os.listdir(f"/proc/{host}/task")) == 1
    # The launcher's process for the diff drive is a trampoline; the node writing its output
    # is the host's child, never exec'ed (it has the server's command line).
    trampoline = controller.pid
    assert any(arg.endswith("fork_trampoline.py") for arg in _cmdline(trampoline))
    node = _node_of(trampoline, host)
    assert _cmdline(node) == _cmdline(server)
    assert _stat(node)[1] == node  # its own session, as a process the launcher starts

    # A request that is not 'python -m MODULE ...' gets no node: the trampoline runs the
    # command itself, and the host goes on serving.
    tramp = _cmdline(trampoline)
    script, socket_path = tramp[tramp.index("-S") + 1], tramp[tramp.index("-S") + 2]
    plain = subprocess.run(
        [sys.executable, "-I", "-S", script, socket_path, "/bin/echo", "run cold"],
        capture_output=True,
        text=True,
        timeout=scaled(30),
        check=False,
    )
    assert (plain.returncode, plain.stdout) == (0, "run cold\n"), plain
    assert "Traceback" not in plain.stderr

    # The node killed: the trampoline ends the same way, and the launcher respawns it.
    os.kill(node, signal.SIGKILL)
    controller.wait_output(in_order(DRIVING, DRIVING), 30)
    assert controller.pid != trampoline
    second = _node_of(controller.pid, host)
    assert second != node
    # The trampoline killed: its node goes with it (and the launcher respawns the pair).
    trampoline = controller.pid
    os.kill(trampoline, signal.SIGKILL)
    _wait_gone(second)
    controller.wait_output(in_order(DRIVING, DRIVING, DRIVING), 30)

    result = handle.stop()
    result.assert_exit_codes({"gzserver": 0, "gazebo_base_controller": {0, -2}})
    _wait_gone(host)
