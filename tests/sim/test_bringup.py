"""Seed 001's launch file, as written, brings the simulated robot up headless."""

from __future__ import annotations

import math
from typing import Any


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
    result = handle.stop()
    result.assert_exit_codes({"gzserver": 0, "spawn_entity.py": 0, "robot_state_publisher": 0})
