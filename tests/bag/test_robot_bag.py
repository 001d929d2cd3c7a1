"""The robot launch records its own topics with ``record:=true`` (the recorder is an
``<executable>`` of the launch, stopped by its Ctrl-C), and that bag replays: a subscriber sees
the same messages, in the same order, with the same stamps."""

from __future__ import annotations

import os
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

import pytest
from rosbags.interfaces import ConnectionExtRosbag2
from rosbags.rosbag2 import Reader

from launchkit.bag.qos import offer_for_recorded
from launchkit.ros.msgs import deserialize, get_message
from launchkit.ros.topics import MessageInfo
from tests.bag.helpers import probe, run_bag
from tests.support import wait_until

TOPICS = ("/clock", "/joint_states", "/odom", "/robot_description", "/scan", "/tf", "/tf_static")
STAMPED = ("/joint_states", "/odom", "/scan")


@pytest.fixture(scope="module")
def robot_bag(launch_module: Any, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A few seconds of the robot recorded by its own launch file; the launch is stopped."""
    bag = tmp_path_factory.mktemp("robot") / "run"
    handle = launch_module(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={
            "start_rviz": "false",
            "record": "true",
            "bag_dir": str(bag),
            "bag_regex": "^(" + "|".join(TOPICS) + ")$",  # not the camera: rendering is costly
        },
        env={"PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"},
        ready_timeout=60,
    )
    recorder = handle.process("bag_record")
    for topic in TOPICS:
        recorder.wait_output(f"Subscribed to topic '{topic}'", timeout=60)
    handle.expect_topic("/scan", min_messages=12, within=60)  # about a second of the robot
    result = handle.stop()
    result.assert_exit_codes({"bag_record": 0, "spawn_entity.py": 0, "*": {0, -2}})
    assert recorder.wait_output("Recording stopped", timeout=1)
    return bag


def test_the_robot_launch_records_its_topics_when_asked(robot_bag: Path) -> None:
    with Reader(robot_bag) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        latched = {
            c.topic
            for c in reader.connections
            if isinstance(c.ext, ConnectionExtRosbag2)
            and all(q.durability.name == "TRANSIENT_LOCAL" for q in c.ext.offered_qos_profiles)
        }
    assert set(counts) == set(TOPICS)
    assert all(counts.values()), counts
    assert {"/robot_description", "/tf_static"} <= latched
    info = run_bag("info", str(robot_bag))
    assert info.returncode == 0, info.stderr
    assert "Topic: /scan | Type: sensor_msgs/msg/LaserScan | Count: " in info.stdout


def test_the_robot_bag_replays_the_same_messages_in_order(router: str, robot_bag: Path) -> None:
    with Reader(robot_bag) as reader:
        recorded = [(c.topic, data) for c, _, data in reader.messages()]
        connections = {c.topic: c for c in reader.connections}
    received: list[tuple[int, str, bytes]] = []  # (player's publish time, topic, bytes)
    with probe(router, "replay_listener") as listener:
        for topic, connection in connections.items():
            ext = connection.ext
            assert isinstance(ext, ConnectionExtRosbag2)
            offered = offer_for_recorded(topic, ext.offered_qos_profiles, print)
            # a queue deep enough for the whole bag: a listener slowed by a busy machine must
            # not drop the oldest messages (KEEP_LAST) while the player runs at twice the rate
            qos = offered.replace(depth=max(offered.depth, len(recorded)))

            def keep(data: bytes, info: MessageInfo, topic: str = topic) -> None:
                received.append((info["source_timestamp"], topic, data))

            listener.node.create_subscription(
                get_message(connection.msgtype), topic, keep, qos, raw=True
            )
        played = run_bag("play", str(robot_bag), "--rate", "2", router=router)
        assert played.returncode == 0, played.stdout + played.stderr
        wait_until(lambda: len(received) >= len(recorded), 20, f"{len(recorded)} messages")

    by_topic: dict[str, list[bytes]] = defaultdict(list)
    for topic, data in recorded:
        by_topic[topic].append(data)
    got: dict[str, list[bytes]] = defaultdict(list)
    for _, topic, data in received:
        got[topic].append(data)
    for topic in TOPICS:
        assert got[topic] == by_topic[topic], (
            f"{topic}: {len(got[topic])} of {len(by_topic[topic])}"
        )
    for topic in STAMPED:
        stamps = [deserialize(d, connections[topic].msgtype).header.stamp for d in got[topic]]
        assert stamps == [
            deserialize(d, connections[topic].msgtype).header.stamp for d in by_topic[topic]
        ]
    # Each subscription has its own delivery thread (as each has its own queue in rclpy), so
    # the order across topics is the player's: the publish times its attachments carry.
    published = [(topic, data) for _, topic, data in sorted(received, key=lambda r: r[0])]
    assert published == recorded, "the order across topics"
