"""One QoS mapping for bags (rosbags' enums) and the bridge (rclpy's): rmw's numbers, both ways."""

from __future__ import annotations

import itertools

import pytest
from rosbags.interfaces import QosDurability, QosHistory, QosReliability

from launchkit.bag.qos import offer_for_recorded, to_bag_qos
from launchkit.ros.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    QoSProfile,
    ReliabilityPolicy,
    known_profile,
)

CONCRETE = [
    QoSProfile(depth=depth, reliability=reliability, durability=durability, history=history)
    for depth, reliability, durability, history in itertools.product(
        (1, 7),
        (ReliabilityPolicy.RELIABLE, ReliabilityPolicy.BEST_EFFORT),
        (DurabilityPolicy.VOLATILE, DurabilityPolicy.TRANSIENT_LOCAL),
        (HistoryPolicy.KEEP_LAST, HistoryPolicy.KEEP_ALL),
    )
]


def test_known_profile_keeps_what_launchkit_implements_and_defaults_the_rest() -> None:
    said = known_profile(
        3,
        QosReliability.BEST_EFFORT.value,
        QosDurability.TRANSIENT_LOCAL.value,
        QosHistory.KEEP_ALL.value,
    )
    assert said == QoSProfile(
        depth=3,
        reliability=ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
        history=HistoryPolicy.KEEP_ALL,
    )
    for other in ("SYSTEM_DEFAULT", "UNKNOWN", "BEST_AVAILABLE"):
        unknown = known_profile(
            5, QosReliability[other].value, QosDurability[other].value, QosHistory.UNKNOWN.value
        )
        assert unknown == QoSProfile(depth=5)  # reliable, volatile, keep last


@pytest.mark.parametrize("profile", CONCRETE, ids=str)
def test_a_bag_records_and_plays_back_each_policy(profile: QoSProfile) -> None:
    recorded = to_bag_qos(profile)
    assert (recorded.reliability.name, recorded.durability.name, recorded.history.name) == (
        profile.reliability.name,
        profile.durability.name,
        profile.history.name,
    )
    said: list[str] = []
    played = offer_for_recorded("/t", [recorded], said.append)
    # rosbag2 plays with the recorded compatibility policies and its default history
    assert played == QoSProfile(
        depth=10, reliability=profile.reliability, durability=profile.durability
    )
    assert not said


@pytest.mark.parametrize("profile", CONCRETE, ids=str)
def test_the_bridge_gives_rclpy_each_policy_and_reads_it_back(profile: QoSProfile) -> None:
    pytest.importorskip("rclpy", reason="the real rclpy (ros2 extra, CPython 3.11 on x86_64)")
    from launchkit.bridge._rclpy import from_rclpy_qos, to_rclpy_qos

    theirs = to_rclpy_qos(profile)
    assert (theirs.reliability.name, theirs.durability.name, theirs.history.name) == (
        profile.reliability.name,
        profile.durability.name,
        profile.history.name,
    )
    assert from_rclpy_qos(theirs, default_depth=42) == profile
