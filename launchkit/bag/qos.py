"""QoS in bags: launchkit profiles to rosbag2's ``offered_qos_profiles`` and back.

rosbag2 stores, for every topic, the QoS each publisher offered when recording began. The
recorder subscribes with a profile adapted to those offers, and the player publishes with one
adapted from them; both rules are rosbag2's (``Rosbag2QoS::adapt_request_to_offers`` and
``adapt_offer_to_recorded_offers``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from rosbags.interfaces import (
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)

from launchkit.ros.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    QoSProfile,
    ReliabilityPolicy,
    known_profile,
)

#: rmw's infinite duration as rosbag2 writes it (deadline, lifespan, liveliness lease).
INFINITE = QosTime(9223372036, 854775807)
#: rosbag2's default depth (``rmw_qos_profile_default``) for what it subscribes and publishes.
DEFAULT_DEPTH = 10

Warn = Callable[[str], object]


def to_bag_qos(profile: QoSProfile) -> Qos:
    """A publisher's profile as one entry of ``offered_qos_profiles``.

    launchkit (like rmw_zenoh's defaults) has no deadline, lifespan or liveliness lease: they
    are written as rmw's infinite duration, liveliness as automatic.
    """
    known = known_profile(profile.depth, profile.reliability, profile.durability, profile.history)
    return Qos(
        QosHistory(int(known.history)),
        known.depth,
        QosReliability(int(known.reliability)),
        QosDurability(int(known.durability)),
        INFINITE,
        INFINITE,
        QosLiveliness.AUTOMATIC,
        INFINITE,
        False,
    )


def request_for_offers(topic: str, offers: Sequence[QoSProfile], warn: Warn) -> QoSProfile:
    """The profile the recorder subscribes with, given the publishers' offers.

    Reliable only if every publisher is, transient local only if every publisher is (then the
    latched samples are recorded too); a mixed topic falls back and says what it loses.
    """
    if not offers:
        return QoSProfile(depth=DEFAULT_DEPTH)
    reliable = sum(p.reliability == ReliabilityPolicy.RELIABLE for p in offers)
    latched = sum(p.durability == DurabilityPolicy.TRANSIENT_LOCAL for p in offers)
    if 0 < reliable < len(offers):
        warn(
            f"Some, but not all, publishers on topic '{topic}' are reliable; subscribing "
            "best effort, so messages of the reliable ones may be dropped"
        )
    if 0 < latched < len(offers):
        warn(
            f"Some, but not all, publishers on topic '{topic}' are transient local; subscribing "
            "volatile, so messages published before recording began are not recorded"
        )
    return QoSProfile(
        depth=DEFAULT_DEPTH,
        reliability=ReliabilityPolicy.RELIABLE
        if reliable == len(offers)
        else ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL
        if latched == len(offers)
        else DurabilityPolicy.VOLATILE,
    )


def _compatibility(qos: Qos) -> tuple[object, ...]:
    # what rosbag2 compares: every policy but history, depth and lifespan
    return (
        qos.reliability,
        qos.durability,
        qos.deadline,
        qos.liveliness,
        qos.liveliness_lease_duration,
    )


def offer_for_recorded(topic: str, recorded: Sequence[Qos], warn: Warn) -> QoSProfile:
    """The profile the player publishes ``topic`` with, given the QoS recorded in the bag.

    When every recorded publisher offered the same compatibility policies, the player offers
    them too (with rosbag2's default history, keep last 10); otherwise rosbag2's default
    profile (reliable, volatile), with a warning.
    """
    if not recorded:
        return QoSProfile(depth=DEFAULT_DEPTH)
    if any(_compatibility(q) != _compatibility(recorded[0]) for q in recorded[1:]):
        warn(
            f"Not all original publishers on topic '{topic}' offered the same QoS profiles; "
            "publishing it with the default profile (reliable, volatile)"
        )
        return QoSProfile(depth=DEFAULT_DEPTH)
    first = recorded[0]
    return known_profile(
        DEFAULT_DEPTH, first.reliability.value, first.durability.value, HistoryPolicy.KEEP_LAST
    )
