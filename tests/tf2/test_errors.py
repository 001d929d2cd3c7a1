"""tf2's exceptions and the exact text of its messages: extrapolation into the past and the
future, unknown, empty and ``/`` frames, unconnected trees, loops, rejected input, and the
frame reports."""

from __future__ import annotations

import math

import pytest

from launchkit.ros.clock import Time
from launchkit.ros.tf2 import (
    BufferCore,
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from tests.tf2.transforms import NS, stamped


@pytest.fixture
def core() -> BufferCore:
    """odom -> base at 10 s and 11 s; base -> laser static; a separate tree world -> sun."""
    core = BufferCore()
    core.set_transform(stamped("odom", "base", 10), "robot")
    core.set_transform(stamped("odom", "base", 11, nanosec=NS // 4), "robot")
    core.set_transform_static(stamped("base", "laser"), "urdf")
    core.set_transform(stamped("world", "sun", 3), "sky")
    return core


def raised(core: BufferCore, target: str, source: str, time: Time) -> TransformException:
    with pytest.raises(TransformException) as caught:
        core.lookup_transform_core(target, source, time)
    return caught.value


def test_the_exceptions_are_tf2s() -> None:
    for exception in (
        ConnectivityException,
        ExtrapolationException,
        InvalidArgumentException,
        LookupException,
        TimeoutException,
    ):
        assert issubclass(exception, TransformException)
        assert exception.__module__ == "tf2"
    assert f"{TransformException.__module__}.{TransformException.__name__}" == (
        "tf2.TransformException"
    )


def test_extrapolation_into_the_future(core: BufferCore) -> None:
    error = raised(core, "odom", "laser", Time(seconds=12))
    assert type(error) is ExtrapolationException
    assert str(error) == (
        "Lookup would require extrapolation into the future.  Requested time 12.000000 but the "
        "latest data is at time 11.250000, when looking up transform from frame [laser] to "
        "frame [odom]"
    )


def test_extrapolation_into_the_past(core: BufferCore) -> None:
    error = raised(core, "laser", "odom", Time(seconds=9, nanoseconds=5))
    assert type(error) is ExtrapolationException
    assert str(error) == (
        "Lookup would require extrapolation into the past.  Requested time 9.000000 but the "
        "earliest data is at time 10.000000, when looking up transform from frame [odom] to "
        "frame [laser]"
    )


def test_one_sample_cannot_be_extrapolated(core: BufferCore) -> None:
    error = raised(core, "world", "sun", Time(seconds=4))
    assert str(error) == (
        "Lookup would require extrapolation at time 4.000000, but only time 3.000000 is in the "
        "buffer, when looking up transform from frame [sun] to frame [world]"
    )


def test_unknown_frames(core: BufferCore) -> None:
    error = raised(core, "map", "base", Time())
    assert type(error) is LookupException
    assert str(error) == '"map" passed to lookupTransform argument target_frame does not exist. '
    error = raised(core, "odom", "gripper", Time())
    assert str(error) == (
        '"gripper" passed to lookupTransform argument source_frame does not exist. '
    )
    assert core.can_transform_core("map", "base", Time()) == (
        0,
        'Invalid frame ID "map" passed to canTransform argument target_frame - '
        "frame does not exist",
    )


def test_empty_and_slashed_frames_are_invalid_arguments(core: BufferCore) -> None:
    error = raised(core, "", "base", Time())
    assert type(error) is InvalidArgumentException
    assert str(error) == (
        'Invalid argument "" passed to lookupTransform argument target_frame - in tf2 frame_ids '
        "cannot be empty"
    )
    error = raised(core, "odom", "/base", Time())
    assert str(error) == (
        'Invalid argument "/base" passed to lookupTransform argument source_frame - in tf2 '
        "frame_ids cannot start with a '/'"
    )
    assert core.can_transform_core("odom", "/base", Time()) == (
        0,
        'Invalid frame ID "/base" passed to canTransform argument source_frame - in tf2 '
        "frame_ids cannot start with a '/'",
    )


def test_frames_of_different_trees_are_not_connected(core: BufferCore) -> None:
    error = raised(core, "odom", "sun", Time(seconds=3))
    assert type(error) is ConnectivityException
    assert str(error) == (
        "Could not find a connection between 'odom' and 'sun' because they are not part of the "
        "same tree.Tf has two or more unconnected trees."
    )
    # as in tf2, a link that cannot answer for the time is reported before the missing
    # connection
    assert type(raised(core, "odom", "sun", Time(seconds=10))) is ExtrapolationException
    # time 0 fails earlier, looking for the latest common time, with the same words
    assert core.can_transform_core("sun", "laser", Time()) == (
        0,
        "Could not find a connection between 'sun' and 'laser' because they are not part of the "
        "same tree.Tf has two or more unconnected trees.",
    )
    with pytest.raises(TransformException) as caught:
        core.get_latest_common_time("sun", "base")
    assert type(caught.value) is TransformException


def test_a_loop_in_the_tree_is_reported_with_the_frames() -> None:
    core = BufferCore()
    core.set_transform(stamped("a", "b", 1), "t")
    core.set_transform(stamped("b", "a", 1), "t")
    core.set_transform(stamped("c", "d", 1), "t")
    error = raised(core, "d", "a", Time(seconds=1))
    assert type(error) is LookupException
    assert str(error) == (
        "The tf tree is invalid because it contains a loop.\n"
        "Frame b exists with parent a.\nFrame a exists with parent b.\n"
        "Frame d exists with parent c.\n\n"
    )


def test_rejected_input_is_logged_and_dropped(capsys: pytest.CaptureFixture[str]) -> None:
    core = BufferCore()
    core.set_transform(stamped("a", "a", 1), "me")
    core.set_transform(stamped("a", "", 1), "me")
    core.set_transform(stamped("", "b", 1), "me")
    core.set_transform(stamped("a", "c", 1, xyz=(math.nan, 0.0, 0.0)), "me")
    core.set_transform(stamped("a", "d", 1, q=(0.0, 0.0, 0.0, 0.0)), "me")
    messages = [line.split("]: ", 1)[1] for line in capsys.readouterr().err.splitlines()]
    assert messages == [
        'TF_SELF_TRANSFORM: Ignoring transform from authority "me" with frame_id and  '
        'child_frame_id "a" because they are the same',
        'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "me" because child_frame_id not '
        "set ",
        'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "b"  from authority "me" because '
        "frame_id not set",
        'TF_NAN_INPUT: Ignoring transform for child_frame_id "c" from authority "me" because of a '
        "nan value in the transform (nan 0.000000 0.000000) (0.000000 0.000000 0.000000 1.000000)",
        'TF_NAN_INPUT: Ignoring transform for child_frame_id "d" from authority "me" because of a '
        "nan value in the transform (0.000000 0.000000 0.000000) (nan nan nan nan)",
    ]
    assert core._getFrameStrings() == []
    assert core.all_frames_as_yaml() == "[]"


def test_frame_reports(core: BufferCore) -> None:
    assert core.all_frames_as_string() == (
        "Frame base exists with parent odom.\n"
        "Frame laser exists with parent base.\n"
        "Frame sun exists with parent world.\n"
    )
    assert core.all_frames_as_yaml() == (
        "base: \n  parent: 'odom'\n  broadcaster: 'robot'\n  rate: 1.600\n"
        "  most_recent_transform: 11.250000\n  oldest_transform: 10.000000\n"
        "  buffer_length: 1.250\n"
        "laser: \n  parent: 'base'\n  broadcaster: 'urdf'\n  rate: 10000.000\n"
        "  most_recent_transform: 0.000000\n  oldest_transform: 0.000000\n"
        "  buffer_length: 0.000\n"
        "sun: \n  parent: 'world'\n  broadcaster: 'sky'\n  rate: 10000.000\n"
        "  most_recent_transform: 3.000000\n  oldest_transform: 3.000000\n"
        "  buffer_length: 0.000\n"
    )


def test_bad_time_arguments_are_type_errors(core: BufferCore) -> None:
    with pytest.raises(TypeError, match=r"^time must have sec and nanosec, or nanoseconds\.$"):
        core.lookup_transform_core("odom", "base", 1.5)
    with pytest.raises(TypeError, match=r"^duration must have sec and nanosec, or nanoseconds\.$"):
        BufferCore(10)
