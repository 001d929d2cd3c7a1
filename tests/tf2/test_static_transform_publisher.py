"""The stock ``tf2_ros`` package's ``static_transform_publisher`` (Jazzy's argument forms,
including the deprecated positional ones with their warning) and ``tf2_echo``: run with
``launchkit exec`` as a user would, and heard by a listener that joins late."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager

import pytest

import launchkit.ros as ros
from launchkit.ros.clock import Duration, Time
from launchkit.ros.tf2 import Buffer, TransformListener
from launchkit.stock.tf2_ros.static_transform_args import (
    OLD_STYLE_WARNING,
    ArgumentError,
    StaticTransform,
    parse,
)
from tests.tf2.transforms import rotation, translation

S = math.sqrt(0.5)


def read(*args: str) -> tuple[StaticTransform | None, list[str]]:
    warnings: list[str] = []
    return parse(list(args), warnings.append).transform, warnings


def test_new_style_flags() -> None:
    transform, warnings = read(
        "--x", "1", "--y", "2", "--z", "3", "--yaw", str(math.pi / 2),
        "--frame-id", "a", "--child-frame-id", "b",
    )  # fmt: skip
    assert transform is not None and not warnings
    assert transform.translation == (1.0, 2.0, 3.0)
    assert transform.rotation == pytest.approx((0.0, 0.0, S, S))
    assert (transform.parent, transform.child) == ("a", "b")
    transform, _ = read("--qz", "1", "--qw", "0", "--frame-id", "a", "--child-frame-id", "b")
    assert transform is not None and transform.rotation == (0.0, 0.0, 1.0, 0.0)
    transform, _ = read("--frame-id", "a", "--child-frame-id", "b")
    assert transform == StaticTransform((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), "a", "b")


def test_old_style_words_are_read_with_a_warning() -> None:
    transform, warnings = read("1", "2", "3", str(math.pi / 2), "0", "0", "map", "odom")
    assert warnings == [OLD_STYLE_WARNING]
    assert transform is not None and transform.translation == (1.0, 2.0, 3.0)
    assert transform.rotation == pytest.approx((0.0, 0.0, S, S))  # yaw pitch roll
    transform, _ = read("1", "2", "3", "0", "0", "1", "0", "map", "odom")  # a quaternion
    assert transform is not None and transform.rotation == (0.0, 0.0, 1.0, 0.0)
    # numbers as C reads them: the number at the start
    transform, _ = read("1.5m", "0", "0", "0", "0", "0", "map", "odom")
    assert transform is not None and transform.translation == (1.5, 0.0, 0.0)


@pytest.mark.parametrize(
    ("args", "reason"),
    [
        (["--x"], "Not enough arguments for --x"),
        (["--x", "one", "--frame-id", "a"], "Failed to parse --x argument as float"),
        (["--qx", "1", "--roll", "1"], "Cannot specify both quaternion and Euler rotations"),
        (["--x", "1", *"1 2 3 0 0 0 a b".split()], "Cannot specify both new-style (flags) and "
         "old-style (arguments)"),
        (["a", "b"], "Extra unparsed arguments on command-line"),
        (["--child-frame-id", "b"], "Frame id must not be empty"),
        (["--frame-id", "a"], "Child frame id must not be empty"),
        ("x 2 3 0 0 0 a b".split(), "Failed to parse x argument as float"),
    ],
)  # fmt: skip
def test_mistakes_are_tf2_ros_reasons(args: list[str], reason: str) -> None:
    with pytest.raises(ArgumentError) as caught:
        read(*args)
    assert caught.value.message == f"error parsing command line arguments: {reason}"
    assert caught.value.exit_status == 2


def test_help_wins() -> None:
    assert parse(["--x", "1", "--help"], print).help


def exec_command(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "launchkit", "exec", "tf2_ros", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )


def stop(process: subprocess.Popen[str]) -> tuple[str, str]:
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
    try:
        return process.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        return process.communicate()


@contextmanager
def listening() -> Iterator[Buffer]:
    """A buffer filled by a listener of the test's own, spinning in its thread."""
    context = ros.Context()
    context.init([])
    node = ros.Node("tf_probe", context=context)
    buffer = Buffer()
    listener = TransformListener(buffer, node, spin_thread=True)
    try:
        yield buffer
    finally:
        del listener
        node.destroy_node()
        context.shutdown()


def test_a_late_listener_gets_the_latched_transform(router: str) -> None:
    publisher = exec_command(
        "static_transform_publisher", "--x", "1", "--y", "2", "--roll", str(math.pi / 2),
        "--frame-id", "world", "--child-frame-id", "camera",
    )  # fmt: skip
    said = []
    try:
        assert publisher.stderr is not None
        # the listener starts only once the transform has been published (the log's last line)
        for line in publisher.stderr:
            said.append(line.rstrip("\n"))
            if line.startswith("from 'world' to 'camera'"):
                break
        with listening() as buffer:
            found = buffer.lookup_transform("world", "camera", Time(), Duration(seconds=60))
        assert translation(found) == (1.0, 2.0, 0.0)
        assert rotation(found) == pytest.approx((S, 0.0, 0.0, S))
    finally:
        stop(publisher)
    assert publisher.returncode == 0
    assert said[-4].startswith("[INFO] ") and said[-4].endswith(
        "]: Spinning until stopped - publishing transform"
    )
    assert "] [static_transform_publisher_" in said[-4]
    assert said[-3:] == [
        "translation: ('1.000000', '2.000000', '0.000000')",
        "rotation: ('0.707107', '0.000000', '0.000000', '0.707107')",
        "from 'world' to 'camera'",
    ]


def test_old_style_arguments_warn_and_tf2_echo_prints_the_transform(router: str) -> None:
    publisher = exec_command("static_transform_publisher", *"0 0 1 0 0 0 base lidar".split())
    echo = exec_command("tf2_echo", "base", "lidar", "5")
    lines = []
    try:
        assert echo.stdout is not None
        for line in echo.stdout:
            lines.append(line.rstrip("\n"))
            if len(lines) >= 10 and lines[-1] == "  0.000  0.000  0.000  1.000":
                break
    finally:
        _, echo_err = stop(echo)
        _, publisher_err = stop(publisher)
    assert lines[-10].startswith("At time ")
    assert lines[-9:] == [
        "- Translation: [0.000, 0.000, 1.000]",
        "- Rotation: in Quaternion [0.000, 0.000, 0.000, 1.000]",
        "- Rotation: in RPY (radian) [0.000, 0.000, 0.000]",
        "- Rotation: in RPY (degree) [0.000, 0.000, 0.000]",
        "- Matrix:",
        "  1.000  0.000  0.000  0.000",
        "  0.000  1.000  0.000  0.000",
        "  0.000  0.000  1.000  1.000",
        "  0.000  0.000  0.000  1.000",
    ]
    first = publisher_err.splitlines()[0]
    assert first.startswith("[WARN] ") and first.endswith(f"] []: {OLD_STYLE_WARNING}")
    assert (echo.returncode, publisher.returncode) == (0, 0), echo_err


def test_a_bad_command_line_is_one_line_and_status_2() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "exec", "tf2_ros", "static_transform_publisher",
         "--x", "1", "--frame-id", "a"],
        capture_output=True,
        text=True,
        timeout=60,
    )  # fmt: skip
    assert result.returncode == 2
    assert result.stderr.splitlines() == [
        "static_transform_publisher: error: error parsing command line arguments: Child frame "
        "id must not be empty (expected --frame-id FRAME_ID --child-frame-id CHILD_FRAME_ID and "
        "the optional --x/--y/--z, --qx/--qy/--qz/--qw or --roll/--pitch/--yaw; see --help)"
    ]


def test_help_prints_tf2_ros_usage() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "exec", "tf2_ros", "static_transform_publisher", "-h"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0
    assert result.stdout.startswith("usage: static_transform_publisher [--x X] [--y Y]")
