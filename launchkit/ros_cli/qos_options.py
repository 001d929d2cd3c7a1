"""``--qos-profile`` and the other ``--qos-*`` options of ``topic echo`` and ``topic pub``, as
ros2topic has them (its presets and short keys), and the profile they make."""

from __future__ import annotations

import argparse
from typing import Any

from launchkit.ros.keyexpr import Token
from launchkit.ros.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

#: rclpy's QoSPresetProfiles by their short keys: (history, depth, reliability, durability)
PRESETS: dict[str, tuple[HistoryPolicy, int, ReliabilityPolicy, DurabilityPolicy]] = {
    "default": (HistoryPolicy.KEEP_LAST, 10, ReliabilityPolicy.RELIABLE, DurabilityPolicy.VOLATILE),
    "system_default": (
        HistoryPolicy.SYSTEM_DEFAULT,
        0,
        ReliabilityPolicy.SYSTEM_DEFAULT,
        DurabilityPolicy.SYSTEM_DEFAULT,
    ),
    "sensor_data": (
        HistoryPolicy.KEEP_LAST,
        5,
        ReliabilityPolicy.BEST_EFFORT,
        DurabilityPolicy.VOLATILE,
    ),
    "services_default": (
        HistoryPolicy.KEEP_LAST,
        10,
        ReliabilityPolicy.RELIABLE,
        DurabilityPolicy.VOLATILE,
    ),
    "parameters": (
        HistoryPolicy.KEEP_LAST,
        1000,
        ReliabilityPolicy.RELIABLE,
        DurabilityPolicy.VOLATILE,
    ),
    "parameter_events": (
        HistoryPolicy.KEEP_LAST,
        1000,
        ReliabilityPolicy.RELIABLE,
        DurabilityPolicy.VOLATILE,
    ),
    "best_available": (
        HistoryPolicy.KEEP_LAST,
        10,
        ReliabilityPolicy.BEST_AVAILABLE,
        DurabilityPolicy.BEST_AVAILABLE,
    ),
    "action_status_default": (
        HistoryPolicy.KEEP_LAST,
        1,
        ReliabilityPolicy.RELIABLE,
        DurabilityPolicy.TRANSIENT_LOCAL,
    ),
}
_RELIABILITY = ("system_default", "reliable", "best_effort", "best_available")
_DURABILITY = ("system_default", "transient_local", "volatile", "best_available")
_HISTORY = ("system_default", "keep_last", "keep_all")
_LIVELINESS = ("system_default", "automatic", "manual_by_topic", "best_available")


def add_qos_arguments(parser: argparse.ArgumentParser, verb: str, default_profile: str) -> None:
    """ros2topic's QoS options; ``verb`` is ``subscribe`` or ``publish``. Liveliness options
    are accepted and have no effect: like rmw_zenoh, launchkit has no liveliness QoS."""
    parser.add_argument(
        "--qos-profile",
        choices=sorted(PRESETS),
        default=default_profile,
        help=f"Quality of service preset profile to {verb} with (default: {default_profile})",
    )
    parser.add_argument(
        "--qos-depth", metavar="N", type=int, help=f"Queue size setting to {verb} with"
    )
    parser.add_argument("--qos-history", choices=_HISTORY, help=f"History setting to {verb} with")
    parser.add_argument(
        "--qos-reliability",
        choices=_RELIABILITY,
        help=f"Reliability setting to {verb} with (default: compatible with the publishers)",
    )
    parser.add_argument(
        "--qos-durability",
        choices=_DURABILITY,
        help=f"Durability setting to {verb} with (default: compatible with the publishers)",
    )
    parser.add_argument("--qos-liveliness", choices=_LIVELINESS, help=argparse.SUPPRESS)
    parser.add_argument(
        "--qos-liveliness-lease-duration-seconds", type=float, help=argparse.SUPPRESS
    )


def overridden(args: argparse.Namespace) -> bool:
    """Whether any ``--qos-*`` setting beyond the preset was given."""
    return any(
        getattr(args, name) is not None
        for name in ("qos_depth", "qos_history", "qos_reliability", "qos_durability")
    )


def profile_from_args(args: argparse.Namespace) -> QoSProfile:
    """The preset of ``--qos-profile`` with the ``--qos-*`` settings applied, as ros2topic's
    ``profile_configure_short_keys`` applies them (a transient-local depth 0 becomes 1)."""
    history, depth, reliability, durability = PRESETS[args.qos_profile]
    if args.qos_history:
        history = HistoryPolicy[args.qos_history.upper()]
    if args.qos_reliability:
        reliability = ReliabilityPolicy[args.qos_reliability.upper()]
    if args.qos_durability:
        durability = DurabilityPolicy[args.qos_durability.upper()]
    if args.qos_depth is not None and args.qos_depth >= 0:
        depth = args.qos_depth
    elif durability == DurabilityPolicy.TRANSIENT_LOCAL and depth == 0:
        depth = 1
    return _profile(history, depth, reliability, durability)


def _profile(history: HistoryPolicy, depth: int, reliability: Any, durability: Any) -> QoSProfile:
    # "best available" left at this point (no publisher to match): rmw's defaults
    if reliability == ReliabilityPolicy.BEST_AVAILABLE:
        reliability = ReliabilityPolicy.RELIABLE
    if durability == DurabilityPolicy.BEST_AVAILABLE:
        durability = DurabilityPolicy.VOLATILE
    return QoSProfile(depth=depth, history=history, reliability=reliability, durability=durability)


def subscription_profile(args: argparse.Namespace, publishers: list[Token]) -> QoSProfile:
    """The QoS ``topic echo`` subscribes with: the ``--qos-*`` settings when any is given, else
    the preset made compatible with every publisher (reliable only if all are, transient local
    only if all are), saying so when the publishers disagree, as ros2 topic echo does."""
    if overridden(args):
        return profile_from_args(args)
    history, depth, reliability, durability = PRESETS[args.qos_profile]
    offered = [t.qos for t in publishers if t.qos is not None]
    if not offered:
        return _profile(history, depth, reliability, durability)
    reliable = sum(q.reliability == ReliabilityPolicy.RELIABLE for q in offered)
    latched = sum(q.durability == DurabilityPolicy.TRANSIENT_LOCAL for q in offered)
    if reliable == len(offered):
        reliability = ReliabilityPolicy.RELIABLE
    else:
        if reliable:
            print(
                "Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. "
                "Falling back to QoSReliabilityPolicy.BEST_EFFORT as it will connect to all "
                "publishers"
            )
        reliability = ReliabilityPolicy.BEST_EFFORT
    if latched == len(offered):
        durability = DurabilityPolicy.TRANSIENT_LOCAL
    else:
        if latched:
            print(
                "Some, but not all, publishers are offering QoSDurabilityPolicy.TRANSIENT_LOCAL. "
                "Falling back to QoSDurabilityPolicy.VOLATILE as it will connect to all "
                "publishers"
            )
        durability = DurabilityPolicy.VOLATILE
    return _profile(history, depth, reliability, durability)
