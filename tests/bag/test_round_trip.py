"""Every message type the ROS layer knows goes through a bag unchanged, and the bag is a rosbag2
bag that rosbags' and mcap's readers read (with the publishers' transient-local QoS kept)."""

from __future__ import annotations

from pathlib import Path

import yaml
from mcap.reader import make_reader
from rosbags.rosbag2 import Reader

from launchkit.bag.selection import TopicSelection
from launchkit.ros.msgs import deserialize, get_message, type_hash, type_names
from launchkit.ros.qos import qos_profile_latched
from tests.bag.helpers import probe, same, sample
from tests.bag.recording import recording


def test_every_message_type_round_trips_through_a_bag(router: str, tmp_path: Path) -> None:
    names = type_names("msg")
    assert len(names) > 150
    sent = {f"/rt/t{i}": (name, sample(name, i)) for i, name in enumerate(names)}
    bag = tmp_path / "all_types"
    with probe(router, "talker") as talker:
        # transient local: published once before recording, the recorder still gets each one
        for topic, (name, message) in sent.items():
            publisher = talker.node.create_publisher(get_message(name), topic, qos_profile_latched)
            publisher.publish(message)
        with recording(router, bag, TopicSelection.build(regex="^/rt/")) as rec:
            rec.discover_until(len(sent))
            rec.wait_received(len(sent), timeout=60)

    with Reader(bag) as reader:
        got = {}
        for connection, _, data in reader.messages():
            assert connection.topic not in got, f"{connection.topic} recorded twice"
            got[connection.topic] = deserialize(data, connection.msgtype)
        assert {c.topic: c.msgtype for c in reader.connections} == {
            t: n for t, (n, _) in sent.items()
        }
    different = [n for t, (n, m) in sent.items() if not same(got[t], m)]
    assert not different, f"changed by the bag: {different}"

    metadata = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert metadata["version"] == 9 and metadata["storage_identifier"] == "mcap"
    assert metadata["message_count"] == len(sent)
    for entry in metadata["topics_with_message_count"]:
        topic = entry["topic_metadata"]
        assert topic["type_description_hash"] == type_hash(topic["type"])
        (offered,) = topic["offered_qos_profiles"]
        assert (offered["durability"], offered["reliability"]) == ("transient_local", "reliable")

    (file,) = metadata["relative_file_paths"]
    with (bag / file).open("rb") as stream:
        mcap = make_reader(stream)
        summary = mcap.get_summary()
        assert summary is not None and summary.statistics is not None
        assert summary.statistics.message_count == len(sent)
        assert mcap.get_header().profile == "ros2"
        assert {s.name for s in summary.schemas.values()} == set(names)
        assert sum(1 for _ in mcap.iter_messages()) == len(sent)
