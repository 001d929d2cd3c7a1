"""The seed robot's transform tree through tf2: while ``gazebo_and_rviz.launch.xml`` runs, a
listener of the test's own looks up ``odom -> base`` (the simulator's diff drive, on /tf), and
``odom -> lidar`` through ``base -> lidar`` (robot_state_publisher's static transform from the
URDF); at the stamp of an /odom message both agree with that message's pose."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from transforms3d.euler import euler2mat
from transforms3d.quaternions import quat2mat

import launchkit.ros as ros
from launchkit.ros.clock import Duration, Time
from launchkit.ros.msgs import get_message
from launchkit.ros.tf2 import Buffer, TransformListener
from tests.tf2.transforms import rotation, translation

# the seed URDF's lidar_joint: <origin xyz="-0.285 0 0.075" rpy="0 0.0 1.57"/>, parent base
LIDAR_XYZ = np.array([-0.285, 0.0, 0.075])
LIDAR_YAW = 1.57
WAIT = Duration(seconds=60)


@pytest.fixture(scope="module")
def robot(launch_module: Any) -> Any:
    """The robot launch, without the viewer."""
    handle = launch_module(
        "robot_wheel", "gazebo_and_rviz.launch.xml", args={"start_rviz": "false"}, ready_timeout=60
    )
    assert handle.process("spawn_entity.py").wait_exit(timeout=60) == 0
    return handle


class Odometry:
    """The /odom messages heard, and a way to wait for the next one."""

    def __init__(self) -> None:
        self.latest: Any = None
        self.arrived = threading.Event()

    def heard(self, message: Any) -> None:
        self.latest = message
        self.arrived.set()

    def next(self) -> Any:
        self.arrived.clear()
        assert self.arrived.wait(60), "no /odom message within 60 s"
        return self.latest


@pytest.fixture
def listener(robot: Any) -> Iterator[tuple[Buffer, Odometry]]:
    """A buffer filled from the robot's /tf and /tf_static, and its /odom messages."""
    context = ros.Context(router=robot.router)
    context.init([], robot.domain_id)
    node = ros.Node("tf2_robot_probe", context=context)
    odometry = Odometry()
    on_odom = odometry.heard

    node.create_subscription(get_message("nav_msgs/msg/Odometry"), "/odom", on_odom, 10)
    buffer = Buffer()
    tf_listener = TransformListener(buffer, node, spin_thread=True)
    try:
        yield buffer, odometry
    finally:
        del tf_listener
        node.destroy_node()
        context.shutdown()


def test_odom_to_base_and_lidar_match_the_odometry(listener: tuple[Buffer, Odometry]) -> None:
    buffer, odometry = listener
    latest = buffer.lookup_transform("odom", "base", Time(), WAIT)
    assert (latest.header.frame_id, latest.child_frame_id) == ("odom", "base")
    buffer.lookup_transform("odom", "lidar", Time(), WAIT)
    # the diff drive sends /odom and /tf from the same update: the transform at the stamp of an
    # /odom message heard from now on is in the buffer, or is on its way
    odom = odometry.next()
    stamp = Time.from_msg(odom.header.stamp)
    base = buffer.lookup_transform("odom", "base", stamp, WAIT)
    pose = odom.pose.pose
    position = (pose.position.x, pose.position.y, pose.position.z)
    orientation = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
    assert translation(base) == pytest.approx(position, abs=1e-9)
    assert same_rotation(rotation(base), orientation)

    lidar = buffer.lookup_transform("odom", "lidar", stamp, WAIT)
    turn = quat2mat([orientation[3], *orientation[:3]])
    assert translation(lidar) == pytest.approx(tuple(turn @ LIDAR_XYZ + position), abs=1e-6)
    expected = turn @ euler2mat(0.0, 0.0, LIDAR_YAW)
    found = rotation(lidar)
    assert np.allclose(quat2mat([found[3], *found[:3]]), expected, atol=1e-6)
    assert buffer.can_transform("odom", "wheel_left_link", Time(), WAIT) == 1


def same_rotation(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    """Equal rotations (q and -q are the same one)."""
    return bool(np.allclose(a, b, atol=1e-9) or np.allclose(a, [-c for c in b], atol=1e-9))
