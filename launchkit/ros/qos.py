"""Quality of service profiles (rclpy names) and their rmw_zenoh encodings."""

from __future__ import annotations

import enum
from dataclasses import dataclass, replace

from launchkit.errors import UserError

ZENOH_DEFAULT_DEPTH = 42  # rmw_zenoh's depth for KEEP_LAST 0 and the default in QoS strings


class ReliabilityPolicy(enum.IntEnum):
    """Whether lost samples are re-sent (rmw enum values)."""

    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(enum.IntEnum):
    """Whether late subscribers get samples published before they joined."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class HistoryPolicy(enum.IntEnum):
    """How many samples are kept."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class QoSError(UserError):
    """An unusable QoS argument."""


@dataclass(frozen=True)
class QoSProfile:
    """A QoS profile: history/depth, reliability, durability (rclpy's constructor names)."""

    depth: int = 10
    reliability: ReliabilityPolicy = ReliabilityPolicy.RELIABLE
    durability: DurabilityPolicy = DurabilityPolicy.VOLATILE
    history: HistoryPolicy = HistoryPolicy.KEEP_LAST

    def __post_init__(self) -> None:
        if self.depth < 0:
            raise QoSError(f"invalid QoS depth {self.depth}", expected="a depth >= 0")
        if self.reliability == ReliabilityPolicy.SYSTEM_DEFAULT:
            object.__setattr__(self, "reliability", ReliabilityPolicy.RELIABLE)
        if self.durability == DurabilityPolicy.SYSTEM_DEFAULT:
            object.__setattr__(self, "durability", DurabilityPolicy.VOLATILE)
        if self.history == HistoryPolicy.SYSTEM_DEFAULT:
            object.__setattr__(self, "history", HistoryPolicy.KEEP_LAST)

    @property
    def effective_depth(self) -> int:
        """The depth a cache uses (rmw_zenoh replaces 0 by 42)."""
        return self.depth or ZENOH_DEFAULT_DEPTH

    def to_keyexpr(self) -> str:
        """rmw_zenoh's QoS string ``R:D:H,depth:DLs,DLns:LSs,LSns:LV,LLs,LLns``.

        As rmw_zenoh 0.2.x writes it (``liveliness_utils.cpp:qos_to_keyexpr`` after
        ``qos.cpp:QoS::best_available_qos``): depth 0 becomes 42, and every field equal to
        rmw_zenoh's default (reliable, volatile, keep last, depth 42, infinite durations,
        automatic liveliness) is left empty.
        """
        rel = "" if self.reliability == ReliabilityPolicy.RELIABLE else str(int(self.reliability))
        dur = "" if self.durability == DurabilityPolicy.VOLATILE else str(int(self.durability))
        hist = "" if self.history == HistoryPolicy.KEEP_LAST else str(int(self.history))
        depth = "" if self.effective_depth == ZENOH_DEFAULT_DEPTH else str(self.depth)
        return f"{rel}:{dur}:{hist},{depth}:,:,:,,"

    @classmethod
    def from_keyexpr(cls, text: str) -> QoSProfile:
        """Parse rmw_zenoh's QoS string (empty fields are rmw_zenoh's defaults).

        Accepts exactly what ``liveliness_utils.cpp:keyexpr_to_qos`` accepts: six ``:`` parts,
        the history, deadline and lifespan parts with two ``,`` fields, liveliness with three,
        known enum numbers and unsigned decimal numbers. Deadline, lifespan and liveliness are
        checked but not kept.
        """
        parts = text.split(":")
        fields = [p.split(",") for p in parts[2:6]]
        if len(parts) < 6 or any(len(f) < n for f, n in zip(fields, (2, 2, 2, 3), strict=True)):
            raise QoSError(f"invalid QoS string {text!r}")
        history, deadline, lifespan, liveliness = fields
        numbers = [history[1], *deadline[:2], *lifespan[:2], *liveliness[1:3]]
        if any(n and not (n.isascii() and n.isdigit() and int(n) < 2**64) for n in numbers):
            raise QoSError(f"invalid QoS string {text!r}")
        enums = ((parts[0], 6), (parts[1], 6), (history[0], 5))
        if any(e not in _ENUM_NUMBERS[:n] for e, n in enums) or liveliness[0] not in _LIVELINESS:
            raise QoSError(f"invalid QoS string {text!r}")
        return cls(
            depth=int(history[1]) if history[1] else ZENOH_DEFAULT_DEPTH,
            reliability=ReliabilityPolicy(int(parts[0])) if parts[0] else _RELIABLE,
            durability=DurabilityPolicy(int(parts[1])) if parts[1] else _VOLATILE,
            history=HistoryPolicy(int(history[0])) if history[0] else _KEEP_LAST,
        )


# the enum numbers rmw_zenoh's str_to_qos_* maps accept ("" is the default); its liveliness
# map has no MANUAL_BY_NODE (2)
_ENUM_NUMBERS = ("", "0", "1", "2", "3", "4")
_LIVELINESS = ("", "0", "1", "3", "4", "5")
_RELIABLE = ReliabilityPolicy.RELIABLE
_VOLATILE = DurabilityPolicy.VOLATILE
_KEEP_LAST = HistoryPolicy.KEEP_LAST


def as_profile(qos: QoSProfile | int) -> QoSProfile:
    """``qos`` as a profile: an int is a KEEP_LAST depth (rclpy's shorthand)."""
    if isinstance(qos, QoSProfile):
        return qos
    if isinstance(qos, bool) or not isinstance(qos, int):
        raise QoSError(f"invalid QoS {qos!r}", expected="a QoSProfile or an int depth")
    return QoSProfile(depth=qos)


def known_profile(depth: int, reliability: int, durability: int, history: int) -> QoSProfile:
    """A profile from policies given by their rmw numbers, which rclpy's, rosbags' and this
    module's enums share: best effort, transient local and keep all where they say so, and
    rmw's defaults (reliable, volatile, keep last) for anything else (system default, unknown,
    best available).

    The one mapping between launchkit and the libraries that speak rmw's enums (bags, the
    bridge's rclpy side), in either direction.
    """
    return QoSProfile(
        depth=depth,
        reliability=ReliabilityPolicy.BEST_EFFORT
        if reliability == ReliabilityPolicy.BEST_EFFORT
        else ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL
        if durability == DurabilityPolicy.TRANSIENT_LOCAL
        else DurabilityPolicy.VOLATILE,
        history=HistoryPolicy.KEEP_ALL
        if history == HistoryPolicy.KEEP_ALL
        else HistoryPolicy.KEEP_LAST,
    )


qos_profile_system_default = QoSProfile()
qos_profile_sensor_data = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_parameters = QoSProfile(depth=1000)
qos_profile_services_default = QoSProfile(depth=10)
qos_profile_clock = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_latched = replace(QoSProfile(depth=1), durability=DurabilityPolicy.TRANSIENT_LOCAL)
