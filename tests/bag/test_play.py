"""``launchkit bag play`` against subscribers in the test process: topic choice, remapping, start
offset, /clock for nodes on sim time, QoS from the bag, loop, bags written by rosbags itself,
and the keyboard on a terminal."""

from __future__ import annotations

import sys
import threading
from pathlib import Path
from typing import Any

import pexpect
from launchkit.ros.msgs.rosgraph_msgs.msg import Clock
from launchkit.ros.msgs.std_msgs.msg import String
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from launchkit.bag.metadata import TopicRecord
from launchkit.bag.qos import to_bag_qos
from launchkit.bag.storage import BagWriter, WriterOptions
from launchkit.ros import DurabilityPolicy, Parameter, QoSProfile, ReliabilityPolicy
from launchkit.ros.msgs import message_definition, serialize, type_hash
from launchkit.ros.qos import qos_profile_latched
from tests.bag.helpers import bag_process, launchkit_env, probe, run_bag
from tests.support import wait_until

NS = 1_000_000_000
T0 = 1_700_000_000 * NS
STRING = "std_msgs/msg/String"
LATCHED = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)


def make_bag(
    path: Path, messages: list[tuple[str, int, Any]], latched: frozenset[str] = frozenset()
) -> Path:
    """A bag of ``(topic, time, message)``; topics in ``latched`` recorded as transient local."""
    writer = BagWriter(path, WriterOptions())
    topics: dict[str, Any] = {}
    for topic, stamp, message in messages:
        if topic not in topics:
            name = message._TYPE_NAME
            qos = qos_profile_latched if topic in latched else QoSProfile(depth=10)
            record = TopicRecord(topic, name, type_hash(name), [to_bag_qos(qos)])
            topics[topic] = writer.add_topic(record, message_definition(name))
        writer.write(topics[topic], stamp, serialize(message))
    writer.close()
    return path


def collect(node: Any, topic: str, qos: QoSProfile | int = 10) -> list[str]:
    """Texts of the strings arriving on ``topic``."""
    texts: list[str] = []
    node.create_subscription(String, topic, lambda m: texts.append(m.data), qos)
    return texts


def test_topics_remap_and_start_offset(router: str, tmp_path: Path) -> None:
    bag = make_bag(
        tmp_path / "bag",
        [("/a" if n % 2 else "/b", T0 + n * NS // 100, String(data=str(n))) for n in range(20)],
    )
    with probe(router) as listener:
        renamed, a, b = (collect(listener.node, t) for t in ("/renamed", "/a", "/b"))
        played = run_bag(
            "play", str(bag), "--topics", "/a", "--remap", "/a:=/renamed",
            "--start-offset", "0.1", router=router,
        )  # fmt: skip
        assert played.returncode == 0, played.stdout + played.stderr
        expected = [str(n) for n in range(11, 20, 2)]
        wait_until(lambda: len(renamed) >= len(expected), 10, f"{expected} on /renamed")
    assert renamed == expected
    assert (a, b) == ([], [])
    assert "Played 5 messages" in played.stderr + played.stdout


def test_clock_drives_nodes_on_sim_time(router: str, tmp_path: Path) -> None:
    span = NS // 2
    messages = [("/a", T0 + n * span // 10, String(data=str(n))) for n in range(11)]
    messages.append(("/clock", T0, Clock()))  # the bag's own /clock is not played with --clock
    bag = make_bag(tmp_path / "bag", sorted(messages, key=lambda m: m[1]))
    sim_time = [Parameter("use_sim_time", value=True)]
    with probe(router, "sim_node", parameter_overrides=sim_time) as node:
        clock = node.node.get_clock()
        seen: list[int] = []
        clocks: list[int] = []
        node.node.create_subscription(
            String, "/a", lambda m: seen.append(clock.now().nanoseconds), 10
        )
        node.node.create_subscription(
            Clock,
            "/clock",
            lambda m: clocks.append(m.clock.sec * NS + m.clock.nanosec),
            QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT),
        )
        played = run_bag("play", str(bag), "--clock", "200", router=router)
        assert played.returncode == 0, played.stdout + played.stderr
        wait_until(lambda: len(seen) == 11, 10, "11 messages on /a")
    # /clock carries bag time (the bag's own /clock, at 0, is not played), and the node's clock
    # follows it: bag time, never the wall clock. The first message and the first /clock leave
    # together, on different topics: a message that overtakes that /clock sees the time a
    # sim-time node has before its first /clock, 0, as in rclpy.
    assert clocks, "no /clock published"
    assert all(T0 <= c < T0 + 10 * NS for c in clocks), [c - T0 for c in clocks]
    assert clocks == sorted(clocks)
    assert all(T0 <= s < T0 + 10 * NS for s in seen if s != 0), [s - T0 for s in seen]
    assert seen.count(0) <= 1 and seen[-1] >= T0 and seen == sorted(seen), seen


def test_transient_local_topics_stay_latched_for_late_subscribers(
    router: str, tmp_path: Path
) -> None:
    messages = [("/latched", T0, String(data="description"))]
    messages += [("/tick", T0 + n * NS // 10, String(data=str(n))) for n in range(1, 25)]
    bag = make_bag(tmp_path / "bag", messages, latched=frozenset({"/latched"}))
    with probe(router) as listener, bag_process(router, "play", str(bag)) as player:
        early = collect(listener.node, "/latched", LATCHED)
        ticks = collect(listener.node, "/tick")
        wait_until(lambda: early == ["description"], 20, "the latched message")
        late = collect(listener.node, "/latched", LATCHED)
        wait_until(lambda: late == ["description"], 10, "the latched message for a late subscriber")
        assert len(ticks) < 24, "the player was still playing"
        (token,) = listener.node.context.graph.tokens("MP", "/latched")
        assert token.qos is not None and token.qos.durability == DurabilityPolicy.TRANSIENT_LOCAL
        assert player.wait(30) == 0, player.output


def test_loop_plays_again_until_interrupted(router: str, tmp_path: Path) -> None:
    bag = make_bag(
        tmp_path / "bag", [("/a", T0 + n * NS // 50, String(data=str(n))) for n in range(5)]
    )
    with probe(router) as listener, bag_process(router, "play", str(bag), "--loop") as player:
        texts = collect(listener.node, "/a")
        wait_until(lambda: len(texts) >= 12, 20, "more than two passes of the bag")
        assert player.interrupt() == 0, player.output
    assert texts[:10] == [str(n) for n in range(5)] * 2


def test_a_bag_written_by_rosbags_itself_plays(router: str, tmp_path: Path) -> None:
    # rosbags' own writer (sqlite3, metadata version 8), with a type launchkit does not know
    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg("string label\nfloat64 value\n", "my_msgs/msg/Reading"))
    reading = store.types["my_msgs/msg/Reading"]
    bag = tmp_path / "outside"
    with Writer(bag, version=8, storage_plugin=StoragePlugin.SQLITE3) as writer:
        text = writer.add_connection("/text", STRING, typestore=store)
        custom = writer.add_connection("/reading", "my_msgs/msg/Reading", typestore=store)
        raw_readings = []
        for n in range(6):
            writer.write(
                text, T0 + n * NS // 100, bytes(store.serialize_cdr(String(data=f"t{n}"), STRING))
            )
            data = bytes(
                store.serialize_cdr(reading(label=f"r{n}", value=n / 2), "my_msgs/msg/Reading")
            )
            raw_readings.append(data)
            writer.write(custom, T0 + n * NS // 100 + 1, data)
    with probe(router) as listener:
        texts = collect(listener.node, "/text")
        raw: list[bytes] = []
        lock = threading.Lock()

        def on_sample(sample: Any) -> None:
            with lock:
                raw.append(sample.payload.to_bytes())

        key = f"{listener.context.domain_id}/reading/**"
        zenoh_sub = listener.context.session.declare_subscriber(key, on_sample)
        with bag_process(router, "play", str(bag)) as player:
            wait_until(lambda: len(texts) == 6 and len(raw) == 6, 20, "every message of the bag")
            assert player.wait(30) == 0, player.output
        zenoh_sub.undeclare()
    assert texts == [f"t{n}" for n in range(6)]
    assert raw == raw_readings, "the unknown type is played from the bag's own definition"


def test_keyboard_pauses_steps_and_resumes(router: str, tmp_path: Path) -> None:
    bag = make_bag(
        tmp_path / "bag", [("/a", T0 + n * NS // 100, String(data=str(n))) for n in range(5)]
    )
    with probe(router) as listener:
        texts = collect(listener.node, "/a")
        player = pexpect.spawn(
            sys.executable,
            ["-m", "launchkit", "bag", "play", str(bag), "--start-paused"],
            env=launchkit_env(router),
            encoding="utf-8",
            timeout=30,
        )
        try:
            player.expect_exact("Press CURSOR_RIGHT for Play Next Message")
            player.send("\x1b[C")  # right arrow: the first message only
            wait_until(lambda: texts == ["0"], 10, "one stepped message")
            player.send("s")  # 's' steps too
            wait_until(lambda: texts == ["0", "1"], 10, "a second stepped message")
            player.send(" ")  # resume: the rest plays
            player.expect_exact("Resuming play.")
            wait_until(lambda: len(texts) == 5, 10, "the rest of the bag")
            player.expect(pexpect.EOF)
        finally:
            player.close(force=True)
    assert player.exitstatus == 0
    assert texts == ["0", "1", "2", "3", "4"]
