"""The bag writer without any transport: splitting, compression, metadata, flushing."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest
import yaml
from launchkit.ros.msgs.std_msgs.msg import String
from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap.records import Message
from mcap.stream_reader import StreamReader
from rosbags.rosbag2 import Reader

from launchkit.bag.metadata import BagError, TopicRecord
from launchkit.bag.qos import to_bag_qos
from launchkit.bag.storage import BagWriter, WriterOptions
from launchkit.ros.msgs import deserialize, message_definition, serialize, type_hash
from launchkit.ros.qos import qos_profile_latched

NS = 1_000_000_000
T0 = 1_700_000_000 * NS


def write_bag(path: Path, options: WriterOptions, count: int = 30, spacing: int = NS // 10) -> None:
    """``count`` strings on /a and /b, ``spacing`` ns apart, ~1 KB each."""
    writer = BagWriter(path, options)
    topics = [
        writer.add_topic(
            TopicRecord(name, "std_msgs/msg/String", type_hash("std_msgs/msg/String"), qos),
            message_definition("std_msgs/msg/String"),
        )
        for name, qos in (("/a", [to_bag_qos(qos_profile_latched)]), ("/b", []))
    ]
    for n in range(count):
        data = serialize(String(data=f"{n:04d}" + "x" * 1000))
        writer.write(topics[n % 2], T0 + n * spacing, data)
    writer.close()


def read_all(path: Path) -> list[tuple[str, int, str]]:
    """(topic, time, text) of every message, through rosbags' reader."""
    with Reader(path) as reader:
        return [(c.topic, t, deserialize(d, c.msgtype).data[:4]) for c, t, d in reader.messages()]


def info(path: Path) -> dict[str, object]:
    """The bag's metadata."""
    document = yaml.safe_load((path / "metadata.yaml").read_text())
    return dict(document["rosbag2_bagfile_information"])


EXPECTED = [("/a" if n % 2 == 0 else "/b", T0 + n * NS // 10, f"{n:04d}") for n in range(30)]


@pytest.mark.parametrize(
    ("options", "files"),
    [
        (WriterOptions(), ["bag_0.mcap"]),
        (WriterOptions(storage="sqlite3"), ["bag_0.db3"]),
        (WriterOptions(storage_preset_profile="zstd_fast"), ["bag_0.mcap"]),
        (WriterOptions(max_bag_duration=NS), ["bag_0.mcap", "bag_1.mcap", "bag_2.mcap"]),
        (WriterOptions(max_bag_size=10_000), [f"bag_{i}.mcap" for i in range(3)]),
        (
            WriterOptions(storage="sqlite3", compression_mode="file", max_bag_duration=2 * NS),
            ["bag_0.db3.zstd", "bag_1.db3.zstd"],
        ),
        (WriterOptions(storage="sqlite3", compression_mode="message"), ["bag_0.db3"]),
    ],
    ids=["mcap", "sqlite3", "zstd-chunks", "split-duration", "split-size", "file-zstd", "msg-zstd"],
)
def test_bags_read_back_whole(tmp_path: Path, options: WriterOptions, files: list[str]) -> None:
    bag = tmp_path / "bag"
    write_bag(bag, options)
    assert sorted(p.name for p in bag.iterdir()) == sorted([*files, "metadata.yaml"])
    assert read_all(bag) == EXPECTED
    meta = info(bag)
    assert meta["relative_file_paths"] == files
    assert meta["message_count"] == 30
    assert meta["starting_time"] == {"nanoseconds_since_epoch": T0}
    assert meta["duration"] == {"nanoseconds": 29 * NS // 10}
    entries = meta["files"]
    assert isinstance(entries, list)
    assert [f["path"] for f in entries] == files
    assert sum(f["message_count"] for f in entries) == 30
    mode = options.compression_mode
    assert (meta["compression_mode"], meta["compression_format"]) == (
        ("", "") if mode == "none" else (mode, "zstd")
    )


def test_metadata_keys_are_in_rosbag2s_order(tmp_path: Path) -> None:
    write_bag(tmp_path / "bag", WriterOptions(custom_data={"robot": "three_wheeled"}), count=2)
    meta = info(tmp_path / "bag")
    assert list(meta) == [
        "version",
        "storage_identifier",
        "duration",
        "starting_time",
        "message_count",
        "topics_with_message_count",
        "compression_format",
        "compression_mode",
        "relative_file_paths",
        "files",
        "custom_data",
        "ros_distro",
    ]
    topics = meta["topics_with_message_count"]
    assert isinstance(topics, list)
    first = topics[0]
    assert list(first) == ["topic_metadata", "message_count"]
    assert list(first["topic_metadata"]) == [
        "name",
        "type",
        "serialization_format",
        "offered_qos_profiles",
        "type_description_hash",
    ]
    assert first["topic_metadata"]["offered_qos_profiles"][0]["durability"] == "transient_local"
    assert meta["custom_data"] == {"robot": "three_wheeled"}
    assert list(meta["files"][0]) == ["path", "starting_time", "duration", "message_count"]


def test_an_open_mcap_holds_every_flushed_chunk(tmp_path: Path) -> None:
    bag = tmp_path / "bag"
    writer = BagWriter(bag, WriterOptions(flush_interval=3600))
    record = TopicRecord("/a", "std_msgs/msg/String", type_hash("std_msgs/msg/String"))
    topic = writer.add_topic(record, message_definition("std_msgs/msg/String"))
    for n in range(5):
        writer.write(topic, T0 + n, serialize(String(data=str(n))))
    writer.flush()  # what the writer does every flush_interval (1 s by default)
    writer.write(topic, T0 + 5, serialize(String(data="not flushed")))
    with (bag / "bag.mcap").open("rb") as stream:  # still being written: no summary, no footer
        texts = []
        with pytest.raises((McapError, struct.error)):  # it ends mid-way, where writing stands
            for record_ in StreamReader(stream).records:
                if isinstance(record_, Message):
                    texts.append(deserialize(record_.data, "std_msgs/msg/String").data)
    assert texts == ["0", "1", "2", "3", "4"]
    writer.close()
    with (bag / "bag_0.mcap").open("rb") as stream:
        assert sum(1 for _ in make_reader(stream).iter_messages()) == 6


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (WriterOptions(storage="lmdb"), "unknown storage"),
        (WriterOptions(storage="sqlite3", storage_preset_profile="zstd_fast"), "sqlite3 has none"),
        (WriterOptions(compression_mode="message"), "does not support message compression"),
        (WriterOptions(storage_preset_profile="fastwrite"), "unknown storage preset"),
    ],
)
def test_options_rosbag2_refuses_are_refused(
    tmp_path: Path, options: WriterOptions, message: str
) -> None:
    with pytest.raises(BagError, match=message):
        BagWriter(tmp_path / "bag", options)
    assert not (tmp_path / "bag").exists()


def test_an_existing_folder_is_never_overwritten(tmp_path: Path) -> None:
    with pytest.raises(BagError, match="already exists"):
        BagWriter(tmp_path, WriterOptions())
