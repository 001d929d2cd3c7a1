"""tf2's buffer maths against transforms worked out by hand (and, for random chains, against
4x4 matrices composed with numpy): direct links, chains through a common parent, interpolation,
time 0, static transforms, the advanced lookup, and how tf2 stores rotations."""

from __future__ import annotations

import itertools
import math
import random

import numpy as np
import pytest
from transforms3d.quaternions import mat2quat, quat2mat

from launchkit.ros.clock import Duration, Time
from launchkit.ros.tf2 import BufferCore, LookupException
from tests.tf2.transforms import NS, rotation, stamp_ns, stamped, translation, yaw

S = math.sqrt(0.5)


def close(actual: tuple[float, ...], expected: tuple[float, ...], tol: float = 1e-9) -> bool:
    return all(abs(a - e) <= tol for a, e in zip(actual, expected, strict=True))


def same_rotation(actual: tuple[float, ...], expected: tuple[float, ...]) -> bool:
    """Equal rotations (q and -q are the same rotation)."""
    return close(actual, expected) or close(actual, tuple(-c for c in expected))


def test_a_direct_link_is_returned_and_inverted() -> None:
    core = BufferCore()
    core.set_transform(stamped("odom", "base", 5, xyz=(1.0, 2.0, 0.0), q=yaw(math.pi / 2)), "t")
    forward = core.lookup_transform_core("odom", "base", Time(seconds=5))
    assert close(translation(forward), (1.0, 2.0, 0.0))
    assert close(rotation(forward), (0.0, 0.0, S, S))
    assert (forward.header.frame_id, forward.child_frame_id) == ("odom", "base")
    # base's origin seen from base is (0, 0, 0); odom's origin, rotated back by -90°, is at
    # (-2, 1) ... in base: R(-90°)·(-1, -2) = (-2, 1)
    inverse = core.lookup_transform_core("base", "odom", Time(seconds=5))
    assert close(translation(inverse), (-2.0, 1.0, 0.0))
    assert close(rotation(inverse), (0.0, 0.0, -S, S))


def test_a_chain_meets_at_the_common_parent() -> None:
    core = BufferCore()
    core.set_transform(stamped("map", "odom", 1, xyz=(10.0, 0.0, 0.0)), "t")
    core.set_transform(stamped("odom", "base", 1, xyz=(0.0, 1.0, 0.0), q=yaw(math.pi / 2)), "t")
    core.set_transform_static(stamped("base", "laser", xyz=(0.5, 0.0, 0.2)), "t")
    core.set_transform(stamped("map", "marker", 1, xyz=(10.0, 3.0, 0.0), q=yaw(math.pi)), "t")
    # the laser in map: (0.5, 0, 0.2) turned by 90° is (0, 0.5, 0.2), + (0, 1, 0) + (10, 0, 0)
    up = core.lookup_transform_core("map", "laser", Time(seconds=1))
    assert close(translation(up), (10.0, 1.5, 0.2))
    assert close(rotation(up), (0.0, 0.0, S, S))
    # seen from the marker (at (10, 3), facing -x): the laser at (10, 1.5) is 1.5 m behind it,
    # to its left: (0, 1.5), and turned by 90° - 180° = -90°
    across = core.lookup_transform_core("marker", "laser", Time(seconds=1))
    assert close(translation(across), (0.0, 1.5, 0.2))
    assert same_rotation(rotation(across), (0.0, 0.0, -S, S))


def test_between_stamps_translation_is_linear_and_rotation_is_slerp() -> None:
    core = BufferCore()
    core.set_transform(stamped("odom", "base", 10, xyz=(0.0, 0.0, 0.0), q=yaw(0.0)), "t")
    core.set_transform(stamped("odom", "base", 20, xyz=(4.0, -2.0, 1.0), q=yaw(math.pi / 2)), "t")
    middle = core.lookup_transform_core("odom", "base", Time(seconds=12, nanoseconds=NS // 2))
    assert close(translation(middle), (1.0, -0.5, 0.25))
    assert close(rotation(middle), yaw(math.pi / 8))  # a quarter of the way from 0 to 90°
    assert stamp_ns(middle) == 12 * NS + NS // 2
    # the short way round: from 170° to -170° passes 180°, not 0°
    core.set_transform(stamped("odom", "turner", 10, q=yaw(math.radians(170))), "t")
    core.set_transform(stamped("odom", "turner", 20, q=yaw(math.radians(-170))), "t")
    half = core.lookup_transform_core("odom", "turner", Time(seconds=15))
    assert same_rotation(rotation(half), yaw(math.pi))


def test_time_zero_is_the_latest_time_every_link_shares() -> None:
    core = BufferCore()
    for sec, x in ((1, 0.0), (2, 1.0), (3, 2.0)):
        core.set_transform(stamped("map", "odom", sec, xyz=(x, 0.0, 0.0)), "t")
    core.set_transform(stamped("odom", "base", 1, xyz=(0.0, 1.0, 0.0)), "t")
    core.set_transform(stamped("odom", "base", 2, nanosec=NS // 2, xyz=(0.0, 2.0, 0.0)), "t")
    latest = core.lookup_transform_core("map", "base", Time())
    assert stamp_ns(latest) == 2 * NS + NS // 2
    assert close(translation(latest), (1.5, 2.0, 0.0))
    assert core.get_latest_common_time("map", "base") == Time(seconds=2, nanoseconds=NS // 2)
    # a frame with itself: its own newest stamp
    assert stamp_ns(core.lookup_transform_core("odom", "odom", Time())) == 3 * NS


def test_static_transforms_hold_at_any_time_and_have_no_time_of_their_own() -> None:
    core = BufferCore()
    core.set_transform_static(stamped("base", "laser", 7, xyz=(0.5, 0.0, 0.0)), "t")
    for when in (Time(), Time(seconds=1), Time(seconds=123456)):
        found = core.lookup_transform_core("base", "laser", when)
        assert close(translation(found), (0.5, 0.0, 0.0))
        assert stamp_ns(found) == when.nanoseconds  # time 0 stays 0: all static
    core.set_transform(stamped("odom", "base", 40, xyz=(1.0, 0.0, 0.0)), "t")
    mixed = core.lookup_transform_core("odom", "laser", Time())
    assert stamp_ns(mixed) == 40 * NS
    assert close(translation(mixed), (1.5, 0.0, 0.0))


def test_a_frame_sent_as_static_then_dynamic_loses_its_static_transform() -> None:
    core = BufferCore()
    core.set_transform_static(stamped("a", "b", xyz=(1.0, 0.0, 0.0)), "t")
    core.set_transform(stamped("a", "b", 5, xyz=(2.0, 0.0, 0.0)), "t")
    assert core.can_transform_core("a", "b", Time(seconds=6)) == (
        0,
        "Lookup would require extrapolation at time 6.000000, but only time 5.000000 is in "
        "the buffer, when looking up transform from frame [b] to frame [a]",
    )


def test_the_advanced_lookup_goes_through_the_fixed_frame() -> None:
    core = BufferCore()
    core.set_transform(stamped("odom", "base", 1, xyz=(0.0, 0.0, 0.0)), "t")
    core.set_transform(stamped("odom", "base", 2, xyz=(1.0, 0.0, 0.0), q=yaw(math.pi / 2)), "t")
    # where a point of base at t=1 is in base at t=2: odom stays put, the robot moved 1 m
    # ahead and turned left, so the old origin is 1 m behind, i.e. to the right: (0, 1)?
    # base(2) sees odom's (0, 0) at R(-90°)·(-1, 0) = (0, 1)
    moved = core.lookup_transform_full_core(
        "base", Time(seconds=2), "base", Time(seconds=1), "odom"
    )
    assert close(translation(moved), (0.0, 1.0, 0.0))
    assert close(rotation(moved), (0.0, 0.0, -S, S))
    assert stamp_ns(moved) == 2 * NS
    assert core.can_transform_full_core("base", Time(seconds=2), "base", Time(seconds=1), "odom")[0]


def test_tf2_keeps_rotations_as_a_matrix_normalised_with_its_sign() -> None:
    core = BufferCore()
    core.set_transform(stamped("a", "minus_w", 1, q=(0.0, 0.0, 0.0, -1.0)), "t")
    core.set_transform(stamped("a", "scaled", 1, q=(0.0, 0.0, 0.0, 2.0)), "t")
    core.set_transform(
        stamped("a", "turned", 1, q=(0.0, 0.0, -0.9659258262890683, 0.25881904510252074)), "t"
    )
    assert close(rotation(core.lookup_transform_core("a", "minus_w", Time())), (0, 0, 0, 1))
    assert close(rotation(core.lookup_transform_core("a", "scaled", Time())), (0, 0, 0, 1))
    # -150° about z: the matrix's trace is negative, so z (the largest diagonal's axis)
    # comes out positive and w negative
    assert close(
        rotation(core.lookup_transform_core("a", "turned", Time())),
        (0.0, 0.0, 0.9659258262890683, -0.25881904510252074),
    )


def test_random_chains_match_composed_matrices() -> None:
    rng = random.Random(24)
    for _ in range(20):
        core = BufferCore()
        matrices = []
        names = [f"f{i}" for i in range(5)]
        for parent, child in itertools.pairwise(names):
            q = np.array([rng.uniform(-1, 1) for _ in range(4)])
            q /= np.linalg.norm(q)
            xyz = tuple(rng.uniform(-5, 5) for _ in range(3))
            core.set_transform(stamped(parent, child, 3, xyz=xyz, q=tuple(q)), "t")
            matrix = np.eye(4)
            matrix[:3, :3] = quat2mat([q[3], q[0], q[1], q[2]])
            matrix[:3, 3] = xyz
            matrices.append(matrix)
        root_to_leaf = matrices[0] @ matrices[1] @ matrices[2] @ matrices[3]
        for target, source, expected in (
            ("f0", "f4", root_to_leaf),
            ("f4", "f0", np.linalg.inv(root_to_leaf)),
            ("f3", "f1", np.linalg.inv(matrices[1] @ matrices[2])),
        ):
            found = core.lookup_transform_core(target, source, Time(seconds=3))
            assert close(translation(found), tuple(expected[:3, 3]), 1e-9)
            w, x, y, z = mat2quat(expected[:3, :3])
            assert same_rotation(rotation(found), (x, y, z, w))


def test_history_is_kept_for_the_cache_time_only(capsys: pytest.CaptureFixture[str]) -> None:
    core = BufferCore(Duration(seconds=2))
    for sec in range(1, 6):
        core.set_transform(stamped("a", "b", sec, xyz=(float(sec), 0.0, 0.0)), "t")
    # as in tf2, each insert first drops what is older than the newest stamp so far minus the
    # cache time: adding 5 s dropped what was before 4 - 2 = 2 s
    assert core.can_transform_core("a", "b", Time(seconds=2))[0] == 1
    assert core.can_transform_core("a", "b", Time(seconds=1)) == (
        0,
        "Lookup would require extrapolation into the past.  Requested time 1.000000 but the "
        "earliest data is at time 2.000000, when looking up transform from frame [b] to frame [a]",
    )
    # the next insert drops 2 s (older than 5 - 2) and takes 3.5 s; older than 3 s is refused
    core.set_transform(stamped("a", "b", 3, nanosec=NS // 2, xyz=(7.0, 0.0, 0.0)), "t")
    assert translation(core.lookup_transform_core("a", "b", Time(seconds=3.5))) == (7.0, 0.0, 0.0)
    assert core.can_transform_core("a", "b", Time(seconds=2))[0] == 0
    core.set_transform(stamped("a", "b", 2, nanosec=NS // 2, xyz=(9.0, 0.0, 0.0)), "t")
    assert core.can_transform_core("a", "b", Time(seconds=2.5))[0] == 0
    assert capsys.readouterr().err.endswith(
        "[]: TF_OLD_DATA ignoring data from the past for frame b at time 2.500000 according to "
        "authority t\nPossible reasons are listed at http://wiki.ros.org/tf/Errors%20explained\n"
    )


def test_clear_forgets_history_but_keeps_static_transforms() -> None:
    core = BufferCore()
    core.set_transform(stamped("a", "b", 1), "t")
    core.set_transform_static(stamped("b", "c"), "t")
    core.clear()
    assert core.can_transform_core("b", "c", Time(seconds=9))[0] == 1
    assert core.can_transform_core("a", "b", Time())[0] == 0


def test_same_frame_lookups_need_no_frame() -> None:
    core = BufferCore()
    found = core.lookup_transform_core("nowhere", "nowhere", Time(seconds=4))
    assert close(rotation(found), (0, 0, 0, 1)) and stamp_ns(found) == 4 * NS
    assert core.can_transform_core("", "", Time()) == (1, "")


def test_frame_existence_and_names() -> None:
    core = BufferCore()
    core.set_transform(stamped("/map", "odom", 1), "t")  # tf2 strips one leading slash
    assert core._frameExists("map") and core._frameExists("odom")
    assert not core._frameExists("/map")
    assert core._getFrameStrings() == ["odom", "map"]
    with pytest.raises(LookupException):
        core.lookup_transform_core("map", "base", Time())
