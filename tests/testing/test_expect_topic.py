"""handle.expect_topic: the test joins the launch's own ROS network and collects messages."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from launchkit.testing import WaitTimeout
from tests.support import ament_package

TALKER = f"""#!{sys.executable}
import launchkit.ros as ros
from launchkit.ros.msgs.std_msgs.msg import String

import sys

word = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else "hello"
ros.init()
node = ros.Node("talker")
chatter = node.create_publisher(String, "chatter", 10)
latched = node.create_publisher(
    String, "latched", ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
)
latched.publish(String(data="published once, at start"))
count = [0]


def tick():
    count[0] += 1
    chatter.publish(String(data=f"{{word}} {{count[0]}}"))


node.create_timer(0.05, tick)
try:
    ros.spin(node)
except (KeyboardInterrupt, ros.ExternalShutdownException):
    pass
ros.try_shutdown()
"""


@pytest.fixture
def talker_launch(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A launch file running a talker node from an AMENT_PREFIX_PATH package."""
    prefix = ament_package(tmp_path / "install", "demo", {"talker": TALKER})
    path = tmp_path / "talk.launch.xml"
    path.write_text(
        '<launch><arg name="word" default="hello"/>'
        '<node pkg="demo" exec="talker" args="$(var word)" output="screen"/></launch>'
    )
    return path, {"AMENT_PREFIX_PATH": str(prefix)}


def test_messages_arrive_and_can_be_filtered(launch, talker_launch) -> None:  # type: ignore[no-untyped-def]
    path, env = talker_launch
    handle = launch(path, env=env)
    messages = handle.expect_topic(
        "/chatter", min_messages=3, within=20, where=lambda m: m.data.startswith("hello")
    )
    assert len(messages) == 3
    numbers = [int(m.data.split()[1]) for m in messages]
    assert numbers == sorted(numbers)


def test_a_latched_message_reaches_a_late_test(launch, talker_launch) -> None:  # type: ignore[no-untyped-def]
    path, env = talker_launch
    handle = launch(path, env=env)
    handle.expect_topic("/chatter", within=20)  # the talker has long published its latched one
    (message,) = handle.expect_topic("/latched", within=10)
    assert message.data == "published once, at start"


def test_a_silent_topic_fails_with_what_was_seen(launch, talker_launch) -> None:  # type: ignore[no-untyped-def]
    path, env = talker_launch
    handle = launch(path, env=env)
    handle.expect_topic("/chatter", within=20)
    with pytest.raises(WaitTimeout) as caught:
        handle.expect_topic("/nothing_here", within=0.5)
    text = str(caught.value)
    assert "1 message(s) on /nothing_here" in text
    assert "/chatter" in text and "talker" in text


def test_two_launches_in_parallel_do_not_hear_each_other(launch, talker_launch) -> None:  # type: ignore[no-untyped-def]
    path, env = talker_launch
    first = launch(path, args={"word": "first"}, env=env)
    second = launch(path, args={"word": "second"}, env=env)
    heard_first = first.expect_topic("/chatter", min_messages=20, within=30)
    heard_second = second.expect_topic("/chatter", min_messages=20, within=30)
    assert {m.data.split()[0] for m in heard_first} == {"first"}
    assert {m.data.split()[0] for m in heard_second} == {"second"}
