"""End to end: the seed's gazebo_and_rviz.launch.xml brings the three-wheeled robot up in
PyBullet, headless; its topics flow, /cmd_vel drives it, and Ctrl-C leaves nothing behind.

The seed robot's wheel conventions are inverted (docs/simulation.md, "Plugins and sensors"): as
in Gazebo, ``linear.x > 0`` moves the base toward its own -x (the caster side, where camera and
lidar look) and ``angular.z > 0`` turns it counter-clockwise.

Two topics come from launchkit's choices where Gazebo would leave the seed without them
(docs/simulation.md): the lidar on ``/scan`` (gazebo_ros: ``/gazebo_lidar/out``) and
``/joint_states`` from the simulator, which stands back while the seed's "second terminal"
``joint_state_publisher`` runs.
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pexpect
import pytest
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3

import launchkit.ros as ros

SCAN = "/scan"


@pytest.fixture(scope="module")
def robot(launch_module):  # type: ignore[no-untyped-def]
    """The robot launch with the obstacle world, without the viewer."""
    handle = launch_module(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={"start_rviz": "false", "world": "obstacles"},
        ready_timeout=60,
    )
    assert handle.process("spawn_entity.py").wait_exit(timeout=60) == 0
    return handle


@contextmanager
def second_terminal(handle: Any, *command: str) -> Iterator[subprocess.Popen[bytes]]:
    """``launchkit exec COMMAND`` beside the launch, as a user's second terminal; Ctrl-C after."""
    process = subprocess.Popen(
        [sys.executable, "-m", "launchkit", "exec", *command],
        env={**os.environ, **handle.ros_env},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        yield process
        process.send_signal(signal.SIGINT)
        assert process.wait(10) == 0
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@contextmanager
def driving(handle: Any, twist: Twist) -> Iterator[None]:
    """Publish ``twist`` on /cmd_vel at 20 Hz from the test while the body runs, then stop."""
    context = ros.Context(router=handle.router)
    context.init([], handle.domain_id)
    node = ros.Node("e2e_driver", context=context, enable_rosout=False)
    publisher = node.create_publisher(Twist, "/cmd_vel", 10)
    node.create_timer(0.05, lambda: publisher.publish(twist))
    stop = threading.Event()

    def spin() -> None:
        while not stop.is_set():
            ros.spin_once(node, timeout_sec=0.05)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    try:
        yield
    finally:
        stop.set()
        spinner.join(5)
        publisher.publish(Twist())
        node.destroy_node()
        context.shutdown()


def stamp(message: Any) -> float:
    """A message's header stamp in seconds."""
    return float(message.header.stamp.sec + message.header.stamp.nanosec * 1e-9)


def yaw(message: Any) -> float:
    """Yaw of an Odometry message's pose."""
    q = message.pose.pose.orientation
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def test_the_robot_spawns_and_its_topics_flow(robot) -> None:  # type: ignore[no-untyped-def]
    (description,) = robot.expect_topic("/robot_description", within=30)
    assert "three_wheeled_robot" in description.data
    (static,) = robot.expect_topic("/tf_static", within=30)
    assert {t.child_frame_id for t in static.transforms} >= {"lidar", "camera"}
    (joints,) = robot.expect_topic("/joint_states", within=30)
    assert set(joints.name) == {"wheel_left_joint", "wheel_right_joint", "caster_joint"}
    # robot_state_publisher turns the simulator's joint states into the wheels' transforms.
    (wheels,) = robot.expect_topic(
        "/tf",
        within=30,
        where=lambda m: "wheel_left_link" in {t.child_frame_id for t in m.transforms},
    )
    assert {t.child_frame_id for t in wheels.transforms} >= {"wheel_right_link", "caster"}
    (odom,) = robot.expect_topic("/odom", within=30)
    assert (odom.header.frame_id, odom.child_frame_id) == ("odom", "base")
    (scan,) = robot.expect_topic(SCAN, within=30)
    assert len(scan.ranges) == 360
    finite = [r for r in scan.ranges if math.isfinite(r)]
    assert finite, "the obstacle world puts something in the lidar's range"
    assert all(scan.range_min <= r <= scan.range_max for r in finite)


def test_linear_x_moves_it_the_commanded_distance(robot) -> None:  # type: ignore[no-untyped-def]
    speed = 0.3
    with driving(robot, Twist(linear=Vector3(x=speed))):
        robot.expect_topic("/odom", within=10, where=lambda m: abs(m.twist.twist.linear.x) > 0.25)
        (start,) = robot.expect_topic("/odom", within=10)
        (truth_start,) = robot.expect_topic("/gazebo/my_robot/ground_truth", within=10)
        robot.expect_topic("/odom", within=20, where=lambda m: stamp(m) >= stamp(start) + 2.0)
        (end,) = robot.expect_topic("/odom", within=10)
        (truth_end,) = robot.expect_topic("/gazebo/my_robot/ground_truth", within=10)
    moved = end.pose.pose.position.x - start.pose.pose.position.x
    expected = speed * (stamp(end) - stamp(start))
    assert moved < 0, "the seed robot drives toward its base -x, as in Gazebo"
    assert abs(abs(moved) - expected) < 0.15 * expected, (moved, expected)
    truth_moved = truth_end.pose.pose.position.x - truth_start.pose.pose.position.x
    assert abs(truth_moved - moved) < 0.1, (truth_moved, moved)
    # The wheels turned in /joint_states, so robot_state_publisher's /tf turns them in a viewer.
    (late,) = robot.expect_topic("/joint_states", within=10, where=lambda m: stamp(m) >= stamp(end))
    angle = dict(zip(late.name, late.position, strict=True))["wheel_left_joint"]
    assert abs(angle) > abs(moved) / 0.15 * 0.8, (angle, moved)


def test_angular_z_turns_it_counter_clockwise(robot) -> None:  # type: ignore[no-untyped-def]
    rate = 0.5
    with driving(robot, Twist(angular=Vector3(z=rate))):
        robot.expect_topic("/odom", within=10, where=lambda m: m.twist.twist.angular.z > 0.4)
        (start,) = robot.expect_topic("/odom", within=10)
        robot.expect_topic("/odom", within=20, where=lambda m: stamp(m) >= stamp(start) + 1.5)
        (end,) = robot.expect_topic("/odom", within=10)
    turned = math.remainder(yaw(end) - yaw(start), math.tau)
    expected = rate * (stamp(end) - stamp(start))
    assert turned > 0
    assert abs(turned - expected) < 0.25 * expected, (turned, expected)


def test_teleop_in_a_second_terminal_drives_the_robot(robot) -> None:  # type: ignore[no-untyped-def]
    teleop = pexpect.spawn(
        sys.executable,
        ["-m", "launchkit", "exec", "teleop_twist_keyboard", "teleop_twist_keyboard"],
        env={**os.environ, **robot.ros_env},
        encoding="utf-8",
        timeout=30,
    )
    try:
        teleop.expect_exact("Moving around:")
        teleop.send("i")  # forward at 0.5 m/s, as in ROS
        robot.expect_topic("/odom", within=20, where=lambda m: abs(m.twist.twist.linear.x) > 0.4)
        teleop.send("k")  # stop
        robot.expect_topic("/odom", within=20, where=lambda m: abs(m.twist.twist.linear.x) < 0.02)
        teleop.sendcontrol("c")
        teleop.expect(pexpect.EOF)
    finally:
        teleop.close(force=True)
    assert teleop.exitstatus == 0


def test_the_seeds_joint_state_publisher_takes_over_joint_states(robot) -> None:  # type: ignore[no-untyped-def]
    gzserver = robot.process("gzserver")
    with second_terminal(robot, "joint_state_publisher", "joint_state_publisher"):
        gzserver.wait_output("another node publishes /joint_states", timeout=30)
        # From now on only joint_state_publisher's zeros arrive, as in the seed's Gazebo flow.
        states = robot.expect_topic("/joint_states", min_messages=6, within=20)
        assert not any(any(m.position) for m in states[-3:]), [m.position for m in states]
    gzserver.wait_output("no other node publishes /joint_states", timeout=30)
    robot.expect_topic("/joint_states", within=20, where=lambda m: any(m.position))


def test_ctrl_c_leaves_nothing_running(robot) -> None:  # type: ignore[no-untyped-def]
    result = robot.stop()  # the plugin fails the test if any process of the launch survives
    assert result.returncode == 0
    result.assert_exit_codes({"spawn_entity.py": 0, "*": {0, -2}})


def test_without_gazebo_only_the_description_runs(launch) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={"start_rviz": "false", "start_gazebo": "false"},
    )
    (description,) = handle.expect_topic("/robot_description", within=30)
    assert description.data.lstrip().startswith("<?xml") or "<robot" in description.data
    (static,) = handle.expect_topic("/tf_static", within=30)
    assert static.transforms
    result = handle.stop()
    assert set(result.exit_codes) == {"robot_state_publisher"}
