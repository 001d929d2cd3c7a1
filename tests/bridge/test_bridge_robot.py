"""The robot launch with ``bridge:=true``: a real rclpy node (Fast DDS) reads /odom and /scan
of the simulated robot, and sees the robot's nodes' topics in its own graph."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest
from bridge_helpers import DDS_ENV, RCLPY_MISSING, DdsPeer, wait_until

pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")


@pytest.fixture(scope="module")
def robot(launch_module: Any) -> Any:
    """The robot launch with the bridge, without the viewer (skips without rclpy)."""
    pytest.importorskip("rclpy", reason=RCLPY_MISSING, exc_type=ImportError)
    return launch_module(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={"start_rviz": "false", "bridge": "true"},
        env=DDS_ENV,
        ready_timeout=60,
    )


@pytest.fixture(scope="module")
def ros2_user(robot: Any) -> Iterator[DdsPeer]:
    """A ROS 2 user's rclpy node in the launch's domain."""
    with pytest.MonkeyPatch.context() as patch:
        for name, value in DDS_ENV.items():
            patch.setenv(name, value)
        peer = DdsPeer(robot.domain_id, "ros2_user")
        yield peer
        peer.close()


def test_an_rclpy_node_reads_odom_and_scan(robot: Any, ros2_user: DdsPeer) -> None:
    from nav_msgs.msg import Odometry
    from rclpy.qos import qos_profile_sensor_data
    from sensor_msgs.msg import LaserScan

    odom: list[Any] = []
    scans: list[Any] = []
    ros2_user.node.create_subscription(Odometry, "/odom", odom.append, 10)
    ros2_user.node.create_subscription(LaserScan, "/scan", scans.append, qos_profile_sensor_data)
    wait_until(lambda: len(odom) >= 3 and len(scans) >= 3, 60, "/odom and /scan in rclpy")
    assert odom[-1].header.frame_id == "odom" and odom[-1].child_frame_id
    assert len(scans[-1].ranges) > 0 and scans[-1].range_max > scans[-1].range_min
    topics = ros2_user.topics()
    assert topics["/odom"] == ["nav_msgs/msg/Odometry"]
    assert robot.process("ros2_bridge").running


def test_the_robot_description_reaches_a_late_rclpy_node(robot: Any, ros2_user: DdsPeer) -> None:
    from rclpy.qos import DurabilityPolicy, QoSProfile
    from std_msgs.msg import String

    described: list[str] = []
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    ros2_user.node.create_subscription(
        String, "/robot_description", lambda m: described.append(m.data), latched
    )
    wait_until(lambda: bool(described), 60, "the latched /robot_description in rclpy")
    assert "three_wheeled_robot" in described[0]
