"""Quality of service profiles (rclpy names) and their rmw_zenoh encodings."""

from __future__ import annotations

import enum
from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

from launchkit.errors import UserError
from launchkit.ros.ros_time import Duration

ZENOH_DEFAULT_DEPTH = 42  # rmw_zenoh's depth for KEEP_LAST 0 and the default in QoS strings


class QoSPolicyEnum(enum.IntEnum):
    """The base of the QoS policy enums (rmw's numbers, rclpy's names)."""

    @classmethod
    def short_keys(cls) -> list[str]:
        """The members' names in lower case (``ros2 topic``'s option values)."""
        return [k.lower() for k in cls.__members__]

    @classmethod
    def get_from_short_key(cls, name: str) -> int:
        """The number of the member named ``name`` (any case)."""
        return int(cls[name.upper()].value)

    @property
    def short_key(self) -> str:
        """This member's name in lower case."""
        return self.name.lower()


class ReliabilityPolicy(QoSPolicyEnum):
    """Whether lost samples are re-sent (rmw enum values)."""

    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(QoSPolicyEnum):
    """Whether late subscribers get samples published before they joined."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class HistoryPolicy(QoSPolicyEnum):
    """How many samples are kept."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class LivelinessPolicy(QoSPolicyEnum):
    """How a publisher shows it is alive."""

    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSHistoryPolicy = HistoryPolicy
QoSLivelinessPolicy = LivelinessPolicy


class QoSPolicyKind(enum.IntEnum):
    """The QoS policies, as events name them (rmw's bits)."""

    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def qos_policy_name_from_kind(policy_kind: QoSPolicyKind | int) -> str:
    """The name of a policy kind."""
    return QoSPolicyKind(policy_kind).name


class QoSError(UserError):
    """An unusable QoS argument."""


class InvalidQoSProfileException(Exception):
    """A profile without a history or depth (rclpy's exception)."""

    def __init__(self, *args: object) -> None:
        super().__init__("Invalid QoSProfile", *args)


_T = TypeVar("_T")


class _Field(Generic[_T]):
    """A profile field that converts what is assigned (an int to its policy enum, as rclpy)."""

    def __init__(self, convert: Callable[[Any], _T], doc: str) -> None:
        self._convert = convert
        self.__doc__ = doc
        self._attribute = ""

    def __set_name__(self, owner: type, name: str) -> None:
        self._attribute = "_" + name

    @overload
    def __get__(self, instance: None, owner: type) -> _Field[_T]: ...

    @overload
    def __get__(self, instance: object, owner: type) -> _T: ...

    def __get__(self, instance: object | None, owner: type) -> _Field[_T] | _T:
        if instance is None:
            return self
        value: _T = getattr(instance, self._attribute)
        return value

    def __set__(self, instance: object, value: Any) -> None:
        setattr(instance, self._attribute, self._convert(value))


def _duration(value: Any) -> Duration:
    if not isinstance(value, Duration):
        raise TypeError(f"expected a Duration, got {value!r}")
    return value


_FIELDS = (
    "history",
    "depth",
    "reliability",
    "durability",
    "lifespan",
    "deadline",
    "liveliness",
    "liveliness_lease_duration",
    "avoid_ros_namespace_conventions",
)


class QoSProfile:
    """A QoS profile, rclpy's: keyword arguments, a history or a depth required, mutable.

    Policies left at SYSTEM_DEFAULT (or BEST_AVAILABLE) are rmw_zenoh's defaults on the wire
    (:meth:`resolved`): reliable, volatile, keep last.
    """

    __slots__ = tuple(f"_{name}" for name in _FIELDS)

    def __init__(self, **kwargs: Any) -> None:
        unknown = set(kwargs) - set(_FIELDS)
        if unknown:
            raise TypeError(f"Invalid arguments passed to constructor: {sorted(unknown)!r}")
        if "history" not in kwargs:
            if "depth" not in kwargs:
                raise InvalidQoSProfileException("History and/or depth settings are required.")
            kwargs["history"] = HistoryPolicy.KEEP_LAST
        self.history = kwargs["history"]
        if self.history == HistoryPolicy.KEEP_LAST and "depth" not in kwargs:
            raise InvalidQoSProfileException("History set to KEEP_LAST without a depth setting.")
        depth = kwargs.get("depth", 10)
        if isinstance(depth, bool) or not isinstance(depth, int) or depth < 0:
            raise QoSError(f"invalid QoS depth {depth!r}", expected="a depth >= 0")
        self.depth = depth
        self.reliability = kwargs.get("reliability", ReliabilityPolicy.RELIABLE)
        self.durability = kwargs.get("durability", DurabilityPolicy.VOLATILE)
        self.lifespan = kwargs.get("lifespan", Duration())
        self.deadline = kwargs.get("deadline", Duration())
        self.liveliness = kwargs.get("liveliness", LivelinessPolicy.SYSTEM_DEFAULT)
        self.liveliness_lease_duration = kwargs.get("liveliness_lease_duration", Duration())
        self.avoid_ros_namespace_conventions = bool(
            kwargs.get("avoid_ros_namespace_conventions", False)
        )

    history = _Field(HistoryPolicy, "The history policy.")
    depth = _Field(int, "How many samples KEEP_LAST keeps.")
    reliability = _Field(ReliabilityPolicy, "The reliability policy.")
    durability = _Field(DurabilityPolicy, "The durability policy.")
    lifespan = _Field(_duration, "How long a sample stays valid.")
    deadline = _Field(_duration, "The longest expected period between samples.")
    liveliness = _Field(LivelinessPolicy, "The liveliness policy.")
    liveliness_lease_duration = _Field(_duration, "How long a publisher counts as alive.")
    avoid_ros_namespace_conventions = _Field(bool, "Whether the topic name is used as is.")

    def _values(self) -> tuple[Any, ...]:
        return tuple(getattr(self, name) for name in _FIELDS)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, QoSProfile) and self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def __str__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)}" for name in _FIELDS)
        return f"{type(self).__name__}({fields})"

    __repr__ = __str__

    def replace(self, **changes: Any) -> QoSProfile:
        """A copy with ``changes`` (a launchkit helper)."""
        values = {name: getattr(self, name) for name in _FIELDS}
        values.update(changes)
        return QoSProfile(**values)

    def resolved(self) -> QoSProfile:
        """This profile as rmw_zenoh uses it: SYSTEM_DEFAULT policies replaced by its defaults
        (reliable, volatile, keep last)."""
        changes: dict[str, Any] = {}
        if self.history == HistoryPolicy.SYSTEM_DEFAULT:
            changes["history"] = HistoryPolicy.KEEP_LAST
        if self.reliability == ReliabilityPolicy.SYSTEM_DEFAULT:
            changes["reliability"] = ReliabilityPolicy.RELIABLE
        if self.durability == DurabilityPolicy.SYSTEM_DEFAULT:
            changes["durability"] = DurabilityPolicy.VOLATILE
        return self.replace(**changes) if changes else self

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
        qos = self.resolved()
        rel = "" if qos.reliability == ReliabilityPolicy.RELIABLE else str(int(qos.reliability))
        dur = "" if qos.durability == DurabilityPolicy.VOLATILE else str(int(qos.durability))
        hist = "" if qos.history == HistoryPolicy.KEEP_LAST else str(int(qos.history))
        depth = "" if qos.effective_depth == ZENOH_DEFAULT_DEPTH else str(qos.depth)
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
        ).resolved()


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
        raise TypeError(f"Expected QoSProfile or int, but received {type(qos)!r}")
    if qos < 0:
        raise ValueError("history depth must be greater than or equal to zero")
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


def _preset(history: int, depth: int, reliability: int, durability: int) -> QoSProfile:
    return QoSProfile(
        history=history,
        depth=depth,
        reliability=reliability,
        durability=durability,
        liveliness=LivelinessPolicy.SYSTEM_DEFAULT,
    )


# rmw's predefined profiles, field for field
qos_profile_unknown = QoSProfile(
    history=3, depth=0, reliability=3, durability=3, liveliness=LivelinessPolicy.UNKNOWN
)
qos_profile_default = _preset(1, 10, 1, 2)
qos_profile_system_default = _preset(0, 0, 0, 0)
qos_profile_sensor_data = _preset(1, 5, 2, 2)
qos_profile_services_default = _preset(1, 10, 1, 2)
qos_profile_parameters = _preset(1, 1000, 1, 2)
qos_profile_parameter_events = _preset(1, 1000, 1, 2)
qos_profile_best_available = QoSProfile(
    history=1,
    depth=10,
    reliability=4,
    durability=4,
    deadline=Duration(nanoseconds=9223372036854775806),
    liveliness=LivelinessPolicy.BEST_AVAILABLE,
    liveliness_lease_duration=Duration(nanoseconds=9223372036854775806),
)
qos_profile_action_status_default = _preset(1, 1, 1, 1)
# rcl's /rosout profile (its 10 s lifespan included)
qos_profile_rosout_default = QoSProfile(
    history=1, depth=1000, reliability=1, durability=1, lifespan=Duration(seconds=10)
)
# launchkit's own
qos_profile_clock = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)


class QoSPresetProfiles(enum.Enum):
    """The predefined profiles by name (``ros2 topic --qos-profile``)."""

    UNKNOWN = qos_profile_unknown
    DEFAULT = qos_profile_default
    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default
    BEST_AVAILABLE = qos_profile_best_available

    @classmethod
    def short_keys(cls) -> list[str]:
        """The names in lower case."""
        return [k.lower() for k in cls.__members__]

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        """The profile named ``name`` (any case)."""
        profile: QoSProfile = cls[name.upper()].value
        return profile
