"""A node in one process: names, per-node arguments, parameters, timers, logging."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import Node, ParameterNotDeclaredException
from launchkit.ros import logging as ros_logging
from launchkit.ros.context import Context


@pytest.fixture
def restore_log_levels() -> Iterator[None]:
    saved = dict(ros_logging._levels), ros_logging._default_level
    yield
    ros_logging._levels.clear()
    ros_logging._levels.update(saved[0])
    ros_logging._default_level = saved[1]


def test_names_args_and_parameters(contexts: Callable[[], Context]) -> None:
    node = Node(
        "n",
        namespace="robot",
        context=contexts(),
        cli_args=["--ros-args", "-r", "chatter:=news", "-p", "rate:=5", "-r", "__node:=renamed"],
    )
    assert node.get_fully_qualified_name() == "/robot/renamed"
    assert node.resolve_topic_name("chatter") == "/robot/news"
    assert node.resolve_topic_name("~/x") == "/robot/renamed/x"
    assert node.resolve_topic_name("/abs") == "/abs"
    assert node.declare_parameter("rate", 1).value == 5
    assert node.declare_parameter("gain", 0.5).value == 0.5
    assert node.get_parameter("use_sim_time").value is False
    with pytest.raises(ParameterNotDeclaredException):
        node.get_parameter("nope")


def test_timer_runs_in_spin_and_cancels(contexts: Callable[[], Context]) -> None:
    node = Node("ticker", context=contexts())
    ticks: list[int] = []
    timer = node.create_timer(0.01, lambda: ticks.append(1))
    spin_until(node, lambda: len(ticks) >= 3, 10, "three timer ticks")
    timer.cancel()
    assert timer.is_canceled()
    count = len(ticks)
    for _ in range(3):
        from launchkit.ros import spin_once

        spin_once(node, timeout_sec=0.02)
    assert len(ticks) == count


def test_publish_checks_the_type(contexts: Callable[[], Context]) -> None:
    node = Node("typed", context=contexts())
    pub = node.create_publisher(String, "x", 10)
    from launchkit.ros.msgs.geometry_msgs.msg import Twist

    with pytest.raises(TypeError, match="expects std_msgs/msg/String"):
        pub.publish(Twist())


def test_log_level_from_ros_args(
    router: str, capsys: pytest.CaptureFixture[str], restore_log_levels: None
) -> None:
    context = Context()
    context.init(["prog", "--ros-args", "--log-level", "warn"])
    try:
        logger = Node("quiet", context=context).get_logger()
        logger.info("not shown")
        logger.warn("shown")
        for _ in range(3):
            logger.error("once", once=True)  # per call site, as rclpy
    finally:
        context.shutdown()
    err = capsys.readouterr().err
    assert "not shown" not in err
    assert "[WARN]" in err and "[quiet]: shown" in err
    assert err.count("once") == 1


def test_warnings_are_coloured_on_a_terminal_only() -> None:
    import os
    import pty
    import subprocess
    import sys

    code = (
        "from launchkit.ros.logging import get_logger; "
        "get_logger('n').warn('careful'); get_logger('n').info('fine')"
    )
    env = {k: v for k, v in os.environ.items() if k != "RCUTILS_COLORIZED_OUTPUT"}
    ours, theirs = pty.openpty()
    with os.fdopen(ours, "rb", buffering=0) as terminal:
        subprocess.run([sys.executable, "-c", code], stderr=theirs, env=env, timeout=60, check=True)
        os.close(theirs)
        seen = b""
        while b"fine" not in seen:
            seen += terminal.read(4096)
    warn, info = seen.decode().splitlines()[:2]
    assert warn.startswith("\x1b[33m[WARN] ") and warn.endswith("careful\x1b[0m")
    assert info.startswith("[INFO] ")  # as rcutils: info stays plain
    piped = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60
    )
    assert piped.stderr.startswith("[WARN] ") and "\x1b" not in piped.stderr
    forced = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env={**env, "RCUTILS_COLORIZED_OUTPUT": "1"},
        timeout=60,
    )
    assert forced.stderr.startswith("\x1b[33m[WARN] ")
