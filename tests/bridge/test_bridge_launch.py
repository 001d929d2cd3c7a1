"""``launchkit run --bridge``: the bridge joins any launch once, as a supervised node."""

from __future__ import annotations

import subprocess
import sys


def _printed(*args: str) -> str:
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "run", *args, "--print"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_run_bridge_adds_the_bridge_node_to_any_launch() -> None:
    printed = _printed("robot_wheel", "hello.launch.xml", "--bridge")
    assert "-m launchkit.bridge --ros-args -r __node:=ros2_bridge" in printed
    assert "launchkit.bridge" not in _printed("robot_wheel", "hello.launch.xml")


def test_run_bridge_uses_the_robot_launchs_own_switch_so_it_runs_once() -> None:
    printed = _printed("robot_wheel", "gazebo_and_rviz.launch.xml", "--bridge")
    assert printed.count("-m launchkit.bridge") == 1
    assert "gazebo_and_rviz.launch.xml:" in printed.split("-m launchkit.bridge")[0].splitlines()[-2]
    assert "launchkit.bridge" not in _printed("robot_wheel", "gazebo_and_rviz.launch.xml")
