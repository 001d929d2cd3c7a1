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


class DurabilityPolicy(enum.IntEnum):
    """Whether late subscribers get samples published before they joined."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2


class HistoryPolicy(enum.IntEnum):
    """How many samples are kept."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2


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
        """rmw_zenoh's QoS string ``R:D:H,depth:DL:LS:LV`` (defaults left empty)."""
        rel = "" if self.reliability == ReliabilityPolicy.RELIABLE else str(int(self.reliability))
        dur = "" if self.durability == DurabilityPolicy.VOLATILE else str(int(self.durability))
        hist = "" if self.history == HistoryPolicy.KEEP_LAST else str(int(self.history))
        depth = "" if self.depth == ZENOH_DEFAULT_DEPTH else str(self.depth)
        return f"{rel}:{dur}:{hist},{depth}:,:,:,,"

    @classmethod
    def from_keyexpr(cls, text: str) -> QoSProfile:
        """Parse rmw_zenoh's QoS string (empty fields are rmw_zenoh's defaults)."""
        try:
            head, depth_part = text.split(",", 2)[:2]
            rel, dur, hist = head.split(":")
            depth_text = depth_part.split(":")[0]
            return cls(
                depth=int(depth_text) if depth_text else ZENOH_DEFAULT_DEPTH,
                reliability=ReliabilityPolicy(int(rel)) if rel else ReliabilityPolicy.RELIABLE,
                durability=DurabilityPolicy(int(dur)) if dur else DurabilityPolicy.VOLATILE,
                history=HistoryPolicy(int(hist)) if hist else HistoryPolicy.KEEP_LAST,
            )
        except ValueError:
            raise QoSError(f"invalid QoS string {text!r}") from None


def as_profile(qos: QoSProfile | int) -> QoSProfile:
    """``qos`` as a profile: an int is a KEEP_LAST depth (rclpy's shorthand)."""
    if isinstance(qos, QoSProfile):
        return qos
    if isinstance(qos, bool) or not isinstance(qos, int):
        raise QoSError(f"invalid QoS {qos!r}", expected="a QoSProfile or an int depth")
    return QoSProfile(depth=qos)


def incompatibility(publisher: QoSProfile, subscription: QoSProfile) -> str | None:
    """Why a publisher cannot feed a subscription under ROS's rules, or None if it can."""
    if (
        publisher.reliability == ReliabilityPolicy.BEST_EFFORT
        and subscription.reliability == ReliabilityPolicy.RELIABLE
    ):
        return "RELIABILITY (best-effort publisher, reliable subscription)"
    if (
        publisher.durability == DurabilityPolicy.VOLATILE
        and subscription.durability == DurabilityPolicy.TRANSIENT_LOCAL
    ):
        return "DURABILITY (volatile publisher, transient-local subscription)"
    return None


qos_profile_system_default = QoSProfile()
qos_profile_sensor_data = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_parameters = QoSProfile(depth=1000)
qos_profile_services_default = QoSProfile(depth=10)
qos_profile_clock = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_latched = replace(QoSProfile(depth=1), durability=DurabilityPolicy.TRANSIENT_LOCAL)
