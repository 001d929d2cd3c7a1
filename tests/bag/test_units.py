"""The small parts without processes: QoS rules, topic selection, the player's clock, keys."""

from __future__ import annotations

import threading

import pytest

from launchkit.bag.keyboard import parse_keys
from launchkit.bag.metadata import BagError
from launchkit.bag.playclock import PlaybackClock, Wait
from launchkit.bag.qos import offer_for_recorded, request_for_offers, to_bag_qos
from launchkit.bag.selection import TopicSelection
from launchkit.ros.qos import (
    DurabilityPolicy,
    QoSProfile,
    ReliabilityPolicy,
    qos_profile_latched,
    qos_profile_sensor_data,
)

RELIABLE, BEST_EFFORT = ReliabilityPolicy.RELIABLE, ReliabilityPolicy.BEST_EFFORT
LATCHED, VOLATILE = DurabilityPolicy.TRANSIENT_LOCAL, DurabilityPolicy.VOLATILE


@pytest.mark.parametrize(
    ("offers", "reliability", "durability", "warnings"),
    [
        ([QoSProfile(depth=10), QoSProfile(depth=1)], RELIABLE, VOLATILE, 0),
        ([qos_profile_latched, qos_profile_latched], RELIABLE, LATCHED, 0),
        ([qos_profile_latched, QoSProfile(depth=10)], RELIABLE, VOLATILE, 1),
        ([qos_profile_sensor_data, QoSProfile(depth=10)], BEST_EFFORT, VOLATILE, 1),
    ],
)
def test_the_recorder_subscribes_as_rosbag2_adapts_to_offers(
    offers: list[QoSProfile],
    reliability: ReliabilityPolicy,
    durability: DurabilityPolicy,
    warnings: int,
) -> None:
    said: list[str] = []
    qos = request_for_offers("/t", offers, said.append)
    assert (qos.reliability, qos.durability, len(said)) == (reliability, durability, warnings)


def test_the_player_offers_what_was_recorded_or_the_default() -> None:
    said: list[str] = []
    latched = offer_for_recorded("/t", [to_bag_qos(qos_profile_latched)] * 2, said.append)
    assert (latched.reliability, latched.durability, latched.depth) == (RELIABLE, LATCHED, 10)
    sensor = offer_for_recorded("/t", [to_bag_qos(qos_profile_sensor_data)], said.append)
    assert sensor.reliability == BEST_EFFORT
    assert not said
    mixed = [to_bag_qos(qos_profile_latched), to_bag_qos(QoSProfile(depth=10))]
    assert offer_for_recorded("/t", mixed, said.append) == QoSProfile(depth=10)
    assert len(said) == 1 and "Not all original publishers" in said[0]


def test_topic_selection_follows_rosbag2() -> None:
    everything = TopicSelection.build(all_topics=True, exclude_regex="camera")
    assert everything.wants("/scan") and not everything.wants("/camera1/image_raw")
    assert not everything.wants("/_hidden") and not everything.wants("/a/_b")
    named = TopicSelection.build(topics=["scan", "/_private"])
    assert named.wants("/scan") and named.wants("/_private") and not named.wants("/odom")
    searched = TopicSelection.build(regex="od", exclude_topics=["/odom"])
    assert searched.wants("/diff_drive/odometry") and not searched.wants("/odom")
    assert TopicSelection.build().empty
    with pytest.raises(BagError, match="--exclude-regex"):
        TopicSelection.build(all_topics=True, exclude_regex="[")


class FakeSteady:
    """A steady clock the test moves by hand (ns)."""

    def __init__(self) -> None:
        self.now = 1_000

    def __call__(self) -> int:
        return self.now


def test_bag_time_follows_rate_pause_and_jumps() -> None:
    steady = FakeSteady()
    clock = PlaybackClock(start=5_000, rate=2.0, steady=steady)
    steady.now += 100
    assert clock.now() == 5_200
    clock.pause()
    steady.now += 1_000
    assert clock.now() == 5_200, "paused: bag time stands still"
    clock.resume()
    steady.now += 10
    assert clock.now() == 5_220, "resumed where it stopped"
    clock.set_rate(0.5)
    steady.now += 100
    assert clock.now() == 5_270
    clock.jump(9_000)
    assert clock.now() == 9_000
    assert clock.toggle() is True and clock.paused


def test_a_step_releases_one_wait_while_paused() -> None:
    clock = PlaybackClock(start=0, paused=True)
    results: list[Wait] = []
    waiter = threading.Thread(target=lambda: results.append(clock.wait_until(10**15)))
    waiter.start()
    assert clock.step()
    waiter.join(5)
    assert results == [Wait.STEP]
    assert not PlaybackClock(start=0).step(), "a step only means something while paused"
    stopped = threading.Thread(target=lambda: results.append(clock.wait_until(10**15)))
    stopped.start()
    clock.stop()
    stopped.join(5)
    assert results == [Wait.STEP, Wait.STOPPED]


def test_terminal_keys_are_read_as_ros2_bag_play_names_them() -> None:
    assert parse_keys(b" \x1b[C\x1b[Ax\x1b[Bs\x1b[D") == [
        "SPACE",
        "CURSOR_RIGHT",
        "CURSOR_UP",
        "CURSOR_DOWN",
        "s",
    ]
