"""``launchkit bag``'s command line: ``info`` prints what ``ros2 bag info`` prints, and mistakes
are one line with exit status 2, before anything runs."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from launchkit.bag.info import file_size, format_info
from launchkit.bag.storage import WriterOptions
from launchkit.testing._isolation import free_loopback_port, router_endpoint
from tests.bag.helpers import run_bag
from tests.bag.test_storage import T0, write_bag


def local(seconds: int, fmt: str) -> str:
    return time.strftime(fmt, time.localtime(seconds))


def test_info_prints_what_ros2_bag_info_prints(tmp_path: Path) -> None:
    bag = tmp_path / "bag"
    write_bag(bag, WriterOptions(max_bag_duration=2 * 10**9), count=30)
    result = run_bag("info", str(bag))
    assert result.returncode == 0, result.stderr
    size = sum(p.stat().st_size for p in bag.iterdir())
    start, end = T0 // 10**9, (T0 + 2_900_000_000) // 10**9
    assert result.stdout == (
        "\n"
        "Files:             bag_0.mcap\n"
        "                   bag_1.mcap\n"
        f"Bag size:          {file_size(size)}\n"
        "Storage id:        mcap\n"
        "ROS Distro:        jazzy\n"
        "Duration:          2.900000000s\n"
        f"Start:             {local(start, '%b %e %Y %H:%M:%S')}.000000000 ({start}.000000000)\n"
        f"End:               {local(end, '%b %e %Y %H:%M:%S')}.900000000 ({end}.900000000)\n"
        "Messages:          30\n"
        "Topic information: Topic: /a | Type: std_msgs/msg/String | Count: 15 | "
        "Serialization Format: cdr\n"
        "                   Topic: /b | Type: std_msgs/msg/String | Count: 15 | "
        "Serialization Format: cdr\n"
        "Service:           0\n"
        "Service information: \n"
    )
    names = run_bag("info", "-t", str(bag))
    assert names.stdout == "/a\n/b\n"


def test_info_counts_service_events_apart() -> None:
    info = {
        "version": 9,
        "storage_identifier": "mcap",
        "duration": {"nanoseconds": 0},
        "starting_time": {"nanoseconds_since_epoch": 0},
        "message_count": 3,
        "relative_file_paths": [],
        "topics_with_message_count": [
            {
                "topic_metadata": {
                    "name": "/add/_service_event",
                    "type": "example_interfaces/srv/AddTwoInts_Event",
                    "serialization_format": "cdr",
                },
                "message_count": 2,
            },
            {
                "topic_metadata": {
                    "name": "/x",
                    "type": "std_msgs/msg/Empty",
                    "serialization_format": "cdr",
                },
                "message_count": 1,
            },
        ],
    }
    text = format_info(Path("."), info)
    assert "Messages:          1\n" in text
    assert "Service:           1\n" in text
    assert text.endswith(
        "Service information: Service: /add | Type: example_interfaces/srv/AddTwoInts | "
        "Event Count: 2 | Serialization Format: cdr"
    )


@pytest.mark.parametrize(
    "size", [(0, "0 B"), (1023, "1023 B"), (1536, "1.5 KiB"), (5 << 20, "5.0 MiB")]
)
def test_sizes_are_formatted_as_rosbag2_does(size: tuple[int, str]) -> None:
    assert file_size(size[0]) == size[1]


def _bag(tmp_path: Path) -> str:
    write_bag(tmp_path / "bag", WriterOptions(), count=2)
    return str(tmp_path / "bag")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["record"], "error: nothing to record (expected -a, topic names or --regex)"),
        (["record", "-a", "-o", "{tmp}"], "already exists"),
        (["record", "/x", "--exclude-regex", "y"], "need -a or --regex"),
        (["record", "-a", "--regex", "("], "--regex '(': missing ), unterminated subpattern"),
        (["record", "-a", "-s", "sqlite3", "--storage-preset-profile", "zstd_fast"], "sqlite3"),
        (["record", "-a", "--compression-mode", "message"], "does not support message"),
        (["record", "-a", "--compression-format", "zstd"], "without a compression mode"),
        (["record", "-a", "--custom-data", "novalue"], "expected KEY=VALUE"),
        (["play", "{tmp}/missing"], "missing: no such bag"),
        (["play", "{tmp}"], "does not exist"),
        (["info", "{tmp}"], "metadata.yaml: missing"),
        (["play", "{bag}", "--remap", "nonsense"], "invalid remapping rule 'nonsense'"),
        (["reindex", "{tmp}"], "no storage files"),
    ],
)
def test_mistakes_are_one_line_and_exit_2(tmp_path: Path, args: list[str], message: str) -> None:
    # a router that nobody runs: the mistake must be found before it matters
    router = router_endpoint(free_loopback_port())
    bag = _bag(tmp_path) if "{bag}" in " ".join(args) else ""
    result = run_bag(*[a.format(tmp=tmp_path, bag=bag) for a in args], router=router)
    assert result.returncode == 2, result.stdout + result.stderr
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) <= 2, result.stderr  # the line, and a hint


def test_record_without_a_router_waits_for_one_saying_so(tmp_path: Path) -> None:
    # as every launchkit command (and an rmw_zenoh node): with no router to start (the suite
    # turns the shared one off), wait for one, say so once, and stop on Ctrl-C as an
    # interrupted command does (130), with nothing recorded
    router = router_endpoint(free_loopback_port())
    env = {**os.environ, "LAUNCHKIT_ROUTER_AUTOSTART": "0"}
    recorder = subprocess.Popen(
        [sys.executable, "-m", "launchkit", "bag", "record", "-a", "-o", str(tmp_path / "bag"),
         "--router", router],
        stderr=subprocess.PIPE, text=True, env=env,
    )  # fmt: skip
    try:
        assert recorder.stderr is not None
        line = recorder.stderr.readline()
        assert f"Unable to connect to a ROS router at {router}: waiting for it" in line, line
        recorder.send_signal(signal.SIGINT)
        _, rest = recorder.communicate(timeout=30)
    finally:
        recorder.kill()
        recorder.wait()
    assert recorder.returncode == 130, rest
    assert "Traceback" not in rest
    assert not (tmp_path / "bag").exists(), "nothing is created without a router"
