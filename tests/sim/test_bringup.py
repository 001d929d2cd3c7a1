"""Seed 001's launch file, as written, brings the simulated robot up headless; the diff drive
runs as a process of the launch (started at gzserver's request), not as gzserver's own child."""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
from typing import Any

from launchkit.testing import in_order

DRIVING = "driving 'my_robot'"  # the diff drive's first log line


def launchkit_cli(handle: Any, *args: str) -> subprocess.CompletedProcess[str]:
    """``launchkit ARGS`` on the launch's ROS network; it must succeed."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args],
        env={**os.environ, **handle.ros_env},
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )


def launcher_log(handle: Any) -> str:
    """What the launcher printed: its lines and every process's prefixed output."""
    return str(handle.launcher_log.read_text())


def test_gazebo_and_rviz_launch_spawns_and_runs_the_robot(launch: Any) -> None:
    handle = launch("robot_wheel", "gazebo_and_rviz.launch.xml", args={"start_rviz": False})
    handle.process("spawn_entity.py").wait_output("Successfully spawned entity [my_robot]", 30)
    assert handle.process("spawn_entity.py").wait_exit(timeout=10) == 0
    odom = handle.expect_topic("/odom", within=20)[-1]
    assert (odom.header.frame_id, odom.child_frame_id) == ("odom", "base")
    scan = handle.expect_topic("/scan", within=20)[-1]
    assert len(scan.ranges) == 360 and all(math.isinf(r) for r in scan.ranges)  # empty world
    assert handle.expect_topic("/clock", within=10)
    handle.process("gzserver").wait_output("started plugin node 'gazebo_base_controller'", 5)
    handle.process("robot_state_publisher").wait_output("publishing robot", 20)

    # The diff drive is a process of the launch: its own output prefix, not gzserver's ...
    controller = handle.process("gazebo_base_controller")
    controller.wait_output(DRIVING, 20)
    prefixed = rf"^\[gazebo_base_controller-\d+\] .*{DRIVING}"
    assert re.search(prefixed, launcher_log(handle), re.MULTILINE)
    assert not any(DRIVING in line for line in handle.process("gzserver").output)
    # ... a ROS node of the launch's network ...
    nodes = launchkit_cli(handle, "node", "list")
    assert "/gazebo_base_controller" in nodes.stdout.split()
    # ... the launcher restarts it when it is killed (the survivor sweep of stop() then covers
    # both incarnations) ...
    first = controller.pid
    os.kill(first, signal.SIGKILL)
    controller.wait_output(in_order(DRIVING, DRIVING), 30)
    assert controller.pid != first
    # ... and deleting the model has the launcher stop it for good.
    deleted = launchkit_cli(
        handle,
        "service",
        "call",
        "--timeout",
        "30",
        "/delete_entity",
        "gazebo_msgs/srv/DeleteEntity",
        "{name: my_robot}",
    )
    assert "success=True" in deleted.stdout or "success: true" in deleted.stdout, deleted.stdout
    assert controller.wait_exit(timeout=20) in (0, -2)

    result = handle.stop()
    respawns = re.findall(r"\[gazebo_base_controller-\d+\]: respawning", launcher_log(handle))
    assert len(respawns) == 1, "respawned after the SIGKILL only, not after the delete"
    result.assert_exit_codes(
        {
            "gzserver": 0,
            "spawn_entity.py": 0,
            "robot_state_publisher": 0,
            "gazebo_base_controller": {0, -2},
        }
    )
