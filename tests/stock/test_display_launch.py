"""The stock nodes together: display.launch.xml (robot_state_publisher, joint_state_publisher_gui,
rviz2) launched for real, checked from a Foxglove client as a user's viewer would see it."""

from __future__ import annotations

from typing import Any

from launchkit.ros.msgs import deserialize
from tests.stock.foxglove_client import receive_topics

TOPICS = ["/robot_description", "/tf_static", "/joint_states", "/tf"]


def test_display_launch_shows_the_robot_in_foxglove(launch: Any) -> None:
    handle = launch("robot_wheel", "display.launch.xml")
    port = handle.viewer_port
    handle.process("rviz2").wait_output(f"ws://127.0.0.1:{port}", timeout=20)

    client = receive_topics(f"ws://127.0.0.1:{port}", list(TOPICS))
    description = deserialize(client.received["/robot_description"][0], "std_msgs/msg/String")
    assert 'robot name="three_wheeled_robot"' in description.data
    static = deserialize(client.received["/tf_static"][0], "tf2_msgs/msg/TFMessage")
    assert {t.child_frame_id for t in static.transforms} == {"camera", "lidar"}
    states = deserialize(client.received["/joint_states"][0], "sensor_msgs/msg/JointState")
    assert list(states.name) == ["wheel_right_joint", "wheel_left_joint", "caster_joint"]
    moving = deserialize(client.received["/tf"][0], "tf2_msgs/msg/TFMessage")
    assert {t.child_frame_id for t in moving.transforms} == {
        "wheel_right_link",
        "wheel_left_link",
        "caster",
    }
    handle.stop().assert_exit_codes({"*": 0})
