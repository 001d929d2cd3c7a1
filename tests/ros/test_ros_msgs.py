"""Message classes behave like rclpy's: defaults, nesting, CDR round trips, type hashes."""

from __future__ import annotations

import array

import pytest

from launchkit.errors import UserError
from launchkit.ros.msgs import deserialize, get_message, get_service, serialize, type_hash


def test_every_field_has_a_default() -> None:
    from launchkit.ros.msgs.geometry_msgs.msg import Quaternion, Twist, Vector3

    twist = Twist()
    assert (twist.linear.x, twist.angular.z) == (0.0, 0.0)
    assert Twist(linear=Vector3(x=1.0)).linear.x == 1.0
    assert Quaternion().w == 1.0  # the .msg default, as rclpy


def test_numeric_sequences_accept_lists() -> None:
    from launchkit.ros.msgs.sensor_msgs.msg import JointState

    msg = JointState(name=["a", "b"], position=[1.0, 2.0])
    msg.velocity = [3, 4]
    assert isinstance(msg.velocity, array.array) and msg.velocity.typecode == "d"
    back = deserialize(serialize(msg), "sensor_msgs/msg/JointState")
    assert back.name == ["a", "b"] and list(back.velocity) == [3.0, 4.0]


def test_cdr_has_header_and_round_trips() -> None:
    from launchkit.ros.msgs.std_msgs.msg import String

    data = serialize(String(data="hi"))
    assert data[:4] == b"\x00\x01\x00\x00"
    assert deserialize(data, "std_msgs/msg/String") == String(data="hi")


def test_trailing_padding_from_fast_cdr_is_accepted() -> None:
    from launchkit.ros.msgs.sensor_msgs.msg import JointState

    data = serialize(JointState(name=["a"], position=[1.0]))
    assert deserialize(data + b"\x00" * 4, "sensor_msgs/msg/JointState").name == ["a"]


def test_known_type_hashes() -> None:
    assert type_hash("std_msgs/msg/String") == (
        "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
    )
    assert type_hash("tf2_msgs/msg/TFMessage") == (
        "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087"
    )
    assert type_hash("std_srvs/srv/SetBool") == (
        "RIHS01_abe9e4bb6b41b40e6789712c00ec8871923e089af3f667a79992a428cff2da0a"
    )


def test_gazebo_services_are_registered() -> None:
    from launchkit.ros.msgs.gazebo_msgs.srv import DeleteEntity, SpawnEntity

    request = SpawnEntity.Request(name="robot", xml="<robot/>")
    assert request.initial_pose.orientation.w == 1.0
    assert SpawnEntity.Response().success is False
    assert DeleteEntity.Request(name="robot").name == "robot"
    assert get_service("gazebo_msgs/srv/SpawnEntity") is SpawnEntity


@pytest.mark.parametrize("name", ["nope_msgs/msg/Foo", "std_msgs/msg/Nope", "a/b/c/d"])
def test_unknown_types_are_user_errors(name: str) -> None:
    with pytest.raises(UserError) as info:
        get_message(name)
    assert "expected" in info.value.format()


def test_packages_import_like_rclpy() -> None:
    from launchkit.ros.msgs.rosgraph_msgs.msg import Clock
    from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

    assert TFMessage().transforms == []
    assert Clock().clock.sec == 0
    with pytest.raises(ImportError):
        __import__("launchkit.ros.msgs.nope_msgs.msg")


def test_an_action_feedback_topic_has_a_message_definition() -> None:
    from rosbags.typesys import get_types_from_msg

    from launchkit.ros.msgs import message_definition

    name = "example_interfaces/action/Fibonacci_FeedbackMessage"
    types = get_types_from_msg(message_definition(name), "example_interfaces/msg/Feedback")
    assert [f for f, _ in types["example_interfaces/msg/Feedback"][1]] == ["goal_id", "feedback"]
    assert "unique_identifier_msgs/msg/UUID" in types
