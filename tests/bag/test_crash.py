"""A recorder killed with SIGKILL leaves a bag that ``launchkit bag reindex`` makes readable,
with every message up to the last flush; an intact bag reindexes to the metadata it had."""

from __future__ import annotations

import resource
import sqlite3
import struct
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest
import yaml
from launchkit.ros.msgs.std_msgs.msg import String
from mcap.exceptions import McapError
from mcap.records import Message
from mcap.stream_reader import StreamReader
from rosbags.rosbag2 import Reader

from launchkit.bag.reindex import reindex
from launchkit.bag.storage import WriterOptions
from launchkit.ros.msgs import deserialize
from tests.bag.helpers import bag_process, probe, run_bag
from tests.bag.test_storage import NS, write_bag
from tests.support import wait_until


def _flushed_messages(path: Path) -> int:
    """Complete messages in an MCAP file that is still being written."""
    count = 0
    if path.exists():
        with path.open("rb") as stream:
            try:
                for record in StreamReader(stream).records:
                    count += isinstance(record, Message)
            except (McapError, struct.error):  # where the writer stands: the rest is not there
                pass
    return count


def _committed_rows(path: Path) -> int:
    try:
        with sqlite3.connect(f"file:{path}?mode=ro", uri=True) as db:
            return int(db.execute("SELECT count(*) FROM messages").fetchone()[0])
    except sqlite3.Error:  # not created yet, or locked by a commit right now
        return 0


CASES: dict[str, tuple[list[str], Callable[[Path], bool], str]] = {
    # split every 2 s (a flush, every second, comes first), files compressed: closed .zstd files
    # and one cut mid-write; how many were closed depends on the machine's pace
    "mcap-split-zstd": (
        ["--storage-preset-profile", "zstd_fast", "-d", "2", "--compression-mode", "file"],
        lambda bag: (bag / "bag_0.mcap.zstd").exists() and _flushed_messages(bag / "bag.mcap") > 0,
        "bag_{}.mcap.zstd",
    ),
    "sqlite3": (["-s", "sqlite3"], lambda bag: _committed_rows(bag / "bag.db3") > 0, "bag_{}.db3"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_killed_recorders_bag_reads_after_reindex(router: str, tmp_path: Path, case: str) -> None:
    options, flushed, files = CASES[case]
    bag = tmp_path / "bag"
    sent = 0
    with probe(router, "counter") as counter:
        publisher = counter.node.create_publisher(String, "/count", 100)
        with bag_process(router, "record", "/count", "-o", str(bag), *options) as recorder:
            recorder.wait_line("Subscribed to topic '/count'")
            wait_until(lambda: publisher.get_subscription_count() == 1, 10, "the recorder's sub")

            def publish_until_flushed() -> bool:
                nonlocal sent
                assert recorder.proc.poll() is None, f"the recorder exited:\n{recorder.output}"
                publisher.publish(String(data=str(sent)))
                sent += 1
                return flushed(bag)

            try:
                wait_until(publish_until_flushed, 60, "a flush to disk")
            except AssertionError as exc:
                listing = {f.name: f.stat().st_size for f in bag.iterdir()}
                raise AssertionError(f"{exc}; {sent} sent; {listing}\n{recorder.output}") from None
            recorder.kill()
    assert not (bag / "metadata.yaml").exists()
    assert run_bag("play", str(bag)).returncode == 2, "unreadable before reindex"

    result = run_bag("reindex", str(bag))
    assert result.returncode == 0, result.stdout + result.stderr
    names = {p.name for p in bag.iterdir()}
    split_files = [files.format(i) for i in range(len(names) - 1)]  # numbered from 0, no gap
    assert names == {*split_files, "metadata.yaml"}, names
    with Reader(bag) as reader:
        texts = [int(deserialize(d, c.msgtype).data) for c, _, d in reader.messages()]
        assert reader.message_count == len(texts)
    assert texts, "the flushed messages are in the bag"
    assert texts == list(range(texts[0], texts[0] + len(texts))), "a prefix, without holes"
    assert texts[-1] < sent
    info = run_bag("info", str(bag))
    assert info.returncode == 0 and f"Messages:          {len(texts)}" in info.stdout


def test_an_intact_bag_reindexes_to_the_same_metadata(tmp_path: Path) -> None:
    bag = tmp_path / "bag"
    write_bag(bag, WriterOptions(max_bag_duration=NS, storage_preset_profile="zstd_fast"))
    before = yaml.safe_load((bag / "metadata.yaml").read_text())
    (bag / "metadata.yaml").unlink()
    reindex(bag, log=lambda _: None)
    after = yaml.safe_load((bag / "metadata.yaml").read_text())
    assert after == before


def test_sigterm_closes_the_bag_as_ctrl_c_does(router: str, tmp_path: Path) -> None:
    bag = tmp_path / "bag"
    with probe(router, "counter") as counter:
        publisher = counter.node.create_publisher(String, "/count", 10)
        with bag_process(router, "record", "-a", "-o", str(bag)) as recorder:
            recorder.wait_line("Subscribed to topic '/count'")
            wait_until(lambda: publisher.get_subscription_count() == 1, 10, "the recorder's sub")
            publisher.publish(String(data="0"))
            recorder.proc.terminate()
            assert recorder.wait(30) == 0, recorder.output
    assert "Recording stopped" in recorder.output
    with Reader(bag) as reader:
        # every node also publishes /parameter_events and /rosout, as in ROS 2; -a records them
        topics = {c.topic for c in reader.connections}
        assert "/count" in topics and topics <= {"/count", "/parameter_events", "/rosout"}


def _file_size_limit(limit: int) -> Callable[[], None]:
    """A child's set-up capping the size of any file it writes at ``limit`` bytes: past it,
    writes fail as on a full disk (EFBIG; Python ignores SIGXFSZ). Unlike a small tmpfs, it
    needs no privileges."""

    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return cap


@pytest.mark.parametrize("compressed", [False, True])
def test_reindex_on_a_full_disk_fails_cleanly_and_loses_nothing(
    tmp_path: Path, compressed: bool
) -> None:
    bag = tmp_path / "bag"
    options = WriterOptions(compression_mode="file") if compressed else WriterOptions()
    write_bag(bag, options, count=300)  # ~300 KB of messages
    (bag / "metadata.yaml").unlink()
    (file,) = sorted(bag.iterdir())
    if not compressed:  # the file a killed recorder was writing: it needs a repair
        file.write_bytes(file.read_bytes()[:-5000])
    before = {p.name: p.read_bytes() for p in bag.iterdir()}
    full = subprocess.run(
        [sys.executable, "-m", "launchkit", "bag", "reindex", str(bag)],
        capture_output=True,
        text=True,
        timeout=60,
        preexec_fn=_file_size_limit(4096),
    )
    assert full.returncode == 1, full.stdout + full.stderr
    assert f"error: {bag}: cannot reindex: File too large" in full.stderr
    assert "Traceback" not in full.stderr + full.stdout
    assert {p.name: p.read_bytes() for p in bag.iterdir()} == before  # nothing half-written
    again = run_bag("reindex", str(bag))
    assert again.returncode == 0, again.stderr
    with Reader(bag) as reader:
        assert reader.message_count > 250
