"""``launchkit topic ...`` against running nodes, compared with what ``ros2 topic`` prints
(ros2cli's ros2topic, Jazzy: its verbs' print statements, rclpy's TopicEndpointInfo and
rosidl_runtime_py's message_to_yaml / message_to_csv)."""

from __future__ import annotations

import re
from collections.abc import Iterator

import pytest
from cli_helpers import graph_of, launchkit
from ros_helpers import Child

ROSOUT_YAML = """stamp:
  sec: 1700000000
  nanosec: 5
level: 20
name: cli_test_log
msg: hello from knobs
file: knobs.py
function: main
line: 42
---
"""


@pytest.fixture(scope="module")
def graph() -> Iterator[list[Child]]:
    """/talker (std_msgs/String on /chatter at 50 Hz) and /knobs (one Log on /rosout)."""
    with graph_of("talker", "knobs") as children:
        yield children


def test_list_type_find_and_info(graph: list[Child]) -> None:
    listed = launchkit("topic", "list").stdout.splitlines()
    assert "/chatter" in listed and "/rosout" in listed and listed == sorted(listed)
    typed = launchkit("topic", "list", "-t").stdout.splitlines()
    assert "/chatter [std_msgs/msg/String]" in typed
    assert "/rosout [rcl_interfaces/msg/Log]" in typed
    assert launchkit("topic", "list", "-c").stdout == f"{len(listed)}\n"
    verbose = launchkit("topic", "list", "-v").stdout
    assert verbose.startswith("Published topics:\n * ")
    assert " * /chatter [std_msgs/msg/String] 1 publisher\n" in verbose
    assert "\n\nSubscribed topics:\n" in verbose and verbose.endswith("\n\n")

    assert launchkit("topic", "type", "/chatter").stdout == "std_msgs/msg/String\n"
    assert launchkit("topic", "find", "std_msgs/msg/String").stdout == "/chatter\n"
    assert launchkit("topic", "find", "-c", "rcl_interfaces/msg/Log").stdout == "1\n"
    assert launchkit("topic", "info", "/chatter").stdout == (
        "Type: std_msgs/msg/String\nPublisher count: 1\nSubscription count: 0\n"
    )
    verbose_info = launchkit("topic", "info", "/chatter", "--verbose").stdout
    assert re.fullmatch(
        r"Type: std_msgs/msg/String\n\n"
        r"Publisher count: 1\n\n"
        r"Node name: talker\n"
        r"Node namespace: /\n"
        r"Topic type: std_msgs/msg/String\n"
        r"Topic type hash: RIHS01_df668c740482bbd48fb39d76a70dfd4bd"
        r"59db1288021743503259e948f6b1a18\n"
        r"Endpoint type: PUBLISHER\n"
        r"GID: ([0-9a-f]{2}\.){15}[0-9a-f]{2}\n"
        r"QoS profile:\n"
        r"  Reliability: RELIABLE\n"
        r"  History \(Depth\): KEEP_LAST \(10\)\n"
        r"  Durability: VOLATILE\n"
        r"  Lifespan: Infinite\n"
        r"  Deadline: Infinite\n"
        r"  Liveliness: AUTOMATIC\n"
        r"  Liveliness lease duration: Infinite\n\n"
        r"Subscription count: 0\n\n",
        verbose_info,
    ), verbose_info


def test_echo_prints_yaml_csv_fields_and_flow_style(graph: list[Child]) -> None:
    assert re.fullmatch(
        r"data: hello \d+\n---\n", launchkit("topic", "echo", "/chatter", "--once").stdout
    )
    field = launchkit("topic", "echo", "/chatter", "--once", "--field", "data").stdout
    assert re.fullmatch(r"hello \d+\n---\n", field)
    assert re.fullmatch(
        r"hello \d+\n", launchkit("topic", "echo", "/chatter", "--once", "--csv").stdout
    )
    flow = launchkit("topic", "echo", "/chatter", "std_msgs/msg/String", "--once", "--flow-style")
    assert re.fullmatch(r"\{data: hello \d+\}\n---\n", flow.stdout)
    bad = launchkit("topic", "echo", "/chatter", "--once", "--field", "nope")
    assert bad.returncode == 2 and "invalid field 'nope'" in bad.stderr


def test_echo_rosout_prints_the_log_messages(graph: list[Child]) -> None:
    # /rosout is transient local: a late echo gets the messages already logged
    selected = ["--once", "--filter", "m.name == 'cli_test_log'"]
    echoed = launchkit("topic", "echo", "/rosout", *selected)
    assert echoed.returncode == 0, echoed.stderr
    assert echoed.stdout == ROSOUT_YAML
    # the filter sees what --field selects, as in ros2 topic echo
    stamp = ["--once", "--field", "stamp", "--filter", "m.sec == 1700000000"]
    assert (
        launchkit("topic", "echo", "/rosout", *stamp).stdout == "sec: 1700000000\nnanosec: 5\n---\n"
    )
    broken = launchkit("topic", "echo", "/rosout", *stamp[:3], "--filter", "m.name == 1")
    assert broken.returncode == 2 and "--filter 'm.name == 1'" in broken.stderr, broken.stderr
    no_str = launchkit("topic", "echo", "/rosout", *selected, "--no-str").stdout
    assert "name: '<string length: <12>>'\nmsg: '<string length: <16>>'\n" in no_str
    csv = launchkit("topic", "echo", "/rosout", *selected, "--csv").stdout
    assert csv == "1700000000,5,20,cli_test_log,hello from knobs,knobs.py,main,42\n"


def test_pub_prints_its_loop_and_reaches_a_subscriber(graph: list[Child]) -> None:
    echo = Child(["-m", "launchkit", "topic", "echo", "/greeting", "std_msgs/msg/String"])
    try:
        # --once waits for one matching subscription, as ros2 topic pub does
        published = launchkit(
            "topic", "pub", "--once", "/greeting", "std_msgs/msg/String", "data: hi"
        )
        assert published.returncode == 0, published.stderr
        assert published.stdout.endswith(
            "publisher: beginning loop\npublishing #1: std_msgs.msg.String(data='hi')\n\n"
        )
        echo.expect("data: hi", timeout=30)
    finally:
        echo.stop()
    times = launchkit(
        "topic",
        "pub",
        "-t",
        "2",
        "-r",
        "20",
        "-w",
        "0",
        "/pair",
        "geometry_msgs/msg/Vector3",
        "{x: 1}",
    )
    assert times.stdout == (
        "publisher: beginning loop\n"
        "publishing #1: geometry_msgs.msg.Vector3(x=1.0, y=0.0, z=0.0)\n\n"
        "publishing #2: geometry_msgs.msg.Vector3(x=1.0, y=0.0, z=0.0)\n\n"
    )
    stamped = launchkit(
        "topic", "pub", "--once", "-w", "0", "/stamped", "std_msgs/msg/Header", "{stamp: now}"
    ).stdout
    stamp = re.search(r"stamp=builtin_interfaces.msg.Time\(sec=(\d+), nanosec=\d+\)", stamped)
    assert stamp is not None and int(stamp.group(1)) > 1_600_000_000, stamped
    from_stdin = launchkit(
        "topic",
        "pub",
        "--once",
        "-w",
        "0",
        "/in",
        "std_msgs/msg/String",
        "--stdin",
        stdin="data: x",
    )
    assert "publishing #1: std_msgs.msg.String(data='x')\n" in from_stdin.stdout


def test_echo_no_arr_summarizes_arrays(graph: list[Child]) -> None:
    pub = Child(
        [
            "-m",
            "launchkit",
            "topic",
            "pub",
            "-r",
            "10",
            "/joints",
            "sensor_msgs/msg/JointState",
            "{name: [a, b], position: [1.0, 2.0]}",
        ]
    )
    try:
        pub.expect("publishing #1", timeout=30)
        echoed = launchkit("topic", "echo", "/joints", "--once", "--no-arr").stdout
    finally:
        pub.stop()
    assert echoed == (
        "header:\n  stamp:\n    sec: 0\n    nanosec: 0\n  frame_id: ''\n"
        "name: '<sequence type: string, length: 2>'\n"
        "position: '<sequence type: double, length: 2>'\n"
        "velocity: '<sequence type: double, length: 0>'\n"
        "effort: '<sequence type: double, length: 0>'\n---\n"
    )


def test_hz_and_bw_report_as_ros2_does(graph: list[Child]) -> None:
    hz = Child(["-m", "launchkit", "topic", "hz", "/chatter"])
    bw = Child(["-m", "launchkit", "topic", "bw", "/chatter", "--window", "20"])
    try:
        rate = hz.expect("average rate: ", timeout=30)
        assert re.fullmatch(r"average rate: \d+\.\d{3}", rate)
        detail = hz.expect("\tmin: ", timeout=10)
        assert re.fullmatch(
            r"\tmin: \d+\.\d{3}s max: \d+\.\d{3}s std dev: \d+\.\d{5}s window: \d+", detail
        )
        bw.expect("Subscribed to [/chatter]", timeout=30)
        # the unit follows the rate, as ros2's: B/s, or KB/s when a busy machine bunches them
        received = bw.expect(" from 20 messages", timeout=30)
        assert re.fullmatch(r"(\d+ B|\d+\.\d\d KB)/s from 20 messages", received), received
        size = r"\d+ B" if received.split("/s")[0].endswith(" B") else r"\d+\.\d\d KB"
        sizes = bw.expect("\tMessage size mean: ", timeout=10)
        assert re.fullmatch(rf"\tMessage size mean: {size} min: {size} max: {size}", sizes), sizes
    finally:
        assert hz.stop() == 0 and bw.stop() == 0
