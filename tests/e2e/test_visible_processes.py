"""Every node of a launch is its own process, visible as itself (issue 23): the pid the launcher
prints (``process started with pid [N]``) is the node's own, a direct child of the launcher
leading its own session, whose command line names the node's module, so that ``pgrep -f``
finds exactly that process; and a signal sent to that pid reaches the node itself."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from launchkit.testing import in_order
from launchkit.testing._deadline import Deadline

T = TypeVar("T")
ROOT = Path(__file__).resolve().parents[2]
STARTED = re.compile(r"^\[INFO\] \[(?P<label>[^\]]+)\]: process started with pid \[(?P<pid>\d+)\]")

#: The long-lived processes of the seed launch: name -> (module, what a user would pgrep -f,
#: its first line of output).
SEED_NODES = {
    "gzserver": (
        "launchkit.stock.gazebo_ros.gzserver",
        "gzserver",
        "world 'default' loaded",
    ),
    "robot_state_publisher": (
        "launchkit.stock.robot_state_publisher.node",
        "robot_state_publisher",
        "publishing robot 'three_wheeled_robot'",
    ),
    "gazebo_base_controller": (
        "launchkit.stock.gazebo_ros.diff_drive_node",
        "diff_drive",
        "driving 'my_robot'",
    ),
    "camera_controller": (
        "launchkit.stock.gazebo_ros.camera_node",
        "camera_node",
        "camera 'camera1'",
    ),
}


def printed(handle: Any, what: str, found: Callable[[list[str]], T | None]) -> T:
    """What ``found`` finds in the lines the launcher printed, once it finds something."""
    deadline = Deadline(30)
    while (result := found(handle.launcher_log.read_text().splitlines())) is None:
        assert not deadline.expired(), f"the launcher did not print {what}"
        time.sleep(0.05)
    return result


def printed_pids(handle: Any, label: str, count: int = 1) -> list[int]:
    """The pids the launcher printed for ``label`` (``name-N``), once it has printed
    ``count`` of them."""

    def pids(lines: list[str]) -> list[int] | None:
        started = [int(m["pid"]) for x in lines if (m := STARTED.match(x)) and m["label"] == label]
        return started if len(started) >= count else None

    return printed(handle, f"{count} pid(s) for {label}", pids)


def printed_line(handle: Any, text: str) -> None:
    """Wait until the launcher has printed a line ending with ``text``."""
    printed(
        handle, repr(text), lambda lines: True if any(x.endswith(text) for x in lines) else None
    )


def pgrep(pattern: str, launcher: int) -> list[int]:
    """``pgrep -f PATTERN`` among the launcher's children (other launches may share the host)."""
    found = subprocess.run(
        ["pgrep", "-f", "-P", str(launcher), pattern], capture_output=True, text=True, check=False
    )
    return sorted(int(pid) for pid in found.stdout.split())


def stat(pid: int) -> tuple[int, int]:
    """(parent pid, session id) of process ``pid``."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return int(fields[1]), int(fields[3])


def check_visible(handle: Any, name: str, module: str, pattern: str) -> int:
    """Check that ``name``'s printed pid is the node itself, running ``python -m module``, and
    the one process ``pgrep -f pattern`` finds among the launcher's; its pid."""
    process = handle.process(name)
    [pid] = printed_pids(handle, process.label)[-1:]
    assert pid == process.pid
    argv = Path(f"/proc/{pid}/cmdline").read_text().split("\0")[:-1]
    assert argv[:3] == [sys.executable, "-m", module], argv
    assert stat(pid) == (handle.pid, pid)  # the launcher's child, leading its own session
    assert pgrep(pattern, handle.pid) == [pid]
    return pid


def test_every_node_of_the_seed_launch_is_its_own_process(launch: Any) -> None:
    handle = launch(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={"start_rviz": False},
        ready_timeout=60,
        allow_exit=["spawn_entity.py"],
    )
    pids = {}
    for name, (module, pattern, first_line) in SEED_NODES.items():
        handle.process(name).wait_output(first_line, timeout=60)
        pids[name] = check_visible(handle, name, module, pattern)

    # SIGINT to robot_state_publisher's pid: that node ends, cleanly, and nothing else does.
    rsp = handle.process("robot_state_publisher")
    os.kill(pids["robot_state_publisher"], signal.SIGINT)
    assert rsp.wait_exit(timeout=20) == 0
    # SIGTERM to the camera's pid: the camera ends and the launcher starts it again, as itself.
    camera = handle.process("camera_controller")
    os.kill(pids["camera_controller"], signal.SIGTERM)
    camera.wait_output(in_order("camera 'camera1'", "camera 'camera1'"), timeout=60)
    respawned = printed_pids(handle, camera.label, count=2)
    assert respawned[0] == pids["camera_controller"] and respawned[1] != respawned[0]
    check_visible(handle, "camera_controller", *SEED_NODES["camera_controller"][:2])
    for name in ("robot_state_publisher", "camera_controller"):
        label = handle.process(name).label
        printed_line(handle, f"[{label}]: process has finished cleanly [pid {pids[name]}]")
        # the signal went to the node, not through the launcher
        assert f"sending signal 'SIGINT' to process[{label}]" not in handle.launcher_log.read_text()
    for name in ("gzserver", "gazebo_base_controller"):
        assert handle.process(name).running and handle.process(name).pid == pids[name]

    result = handle.stop()
    result.assert_exit_codes({"spawn_entity.py": 0, "*": {0, -2}})


def test_spawn_entity_is_its_own_process(launch: Any, tmp_path: Path) -> None:
    # With no simulator it waits for /spawn_entity: long enough to look at it, and to stop it.
    launch_file = tmp_path / "spawn.launch.xml"
    urdf = ROOT / "urdf" / "three_wheeled_robot.urdf"
    launch_file.write_text(
        '<launch><node pkg="gazebo_ros" exec="spawn_entity.py" name="spawner" output="screen" '
        f'args="-entity lonely -file {urdf} -spawn_service_timeout 300"/></launch>\n'
    )
    handle = launch(launch_file)
    spawner = handle.process("spawn_entity.py")
    spawner.wait_output("Waiting for service /spawn_entity", timeout=60)
    module = "launchkit.stock.gazebo_ros.spawn_entity"
    pid = check_visible(handle, "spawn_entity.py", module, "spawn_entity")
    os.kill(pid, signal.SIGTERM)
    assert spawner.wait_exit(timeout=20) == 0
    printed_line(handle, f"[{spawner.label}]: process has finished cleanly [pid {pid}]")
    handle.stop()
