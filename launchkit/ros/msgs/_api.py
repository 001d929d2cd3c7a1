"""Lookup, CDR encoding and hashes of message, service and action types (by ``pkg/kind/Name``)."""

from __future__ import annotations

from typing import Any

from launchkit.ros.msgs._classes import ActionType, MessageMeta, ServiceType
from launchkit.ros.msgs._codec import Codec
from launchkit.ros.msgs._registry import MessageTypeError, registry
from launchkit.ros.msgs._spec import MessageSpec

_EXAMPLES = {
    "msg": "geometry_msgs/msg/Twist",
    "srv": "std_srvs/srv/Trigger",
    "action": "example_interfaces/action/Fibonacci",
}
_WHAT = {"msg": "message", "srv": "service", "action": "action"}


def normalize_type_name(name: str, kind: str = "msg") -> str:
    """``pkg/Name`` or ``pkg/msg/Name`` (also ``pkg::msg::Name``) to ``pkg/<kind>/Name``."""
    parts = name.replace("::", "/").strip("/").split("/")
    if len(parts) == 2:
        parts = [parts[0], kind, parts[1]]
    if len(parts) != 3 or not all(parts):
        raise MessageTypeError(
            f"malformed {_WHAT[kind]} type {name!r} "
            f"(expected pkg/{kind}/Name, e.g. {_EXAMPLES[kind]})"
        )
    return "/".join(parts)


def type_names(kind: str = "msg", discover: bool = False) -> list[str]:
    """Every known type name of a kind (``msg``, ``srv`` or ``action``), sorted: the built-in
    ones and those of packages read so far; ``discover``: first read every package the package
    index finds with interface folders (what ``launchkit interface list`` shows)."""
    reg = registry()
    if discover:
        reg.names(kind, reg.discovered_packages())  # reads their files
    return reg.names(kind)


def packages() -> set[str]:
    """Names of the packages of the built-in store (messages and services)."""
    return registry().builtin_packages()


def get_message(name: str) -> Any:
    """The message class for ``pkg/msg/Name`` (or ``pkg/Name``)."""
    full = normalize_type_name(name, "msg")
    try:
        return registry().message_class(full)
    except (KeyError, ValueError):
        raise MessageTypeError(
            f"unknown message type {name!r} (expected a ROS 2 Jazzy type such as "
            f"std_msgs/msg/String or one of a package's msg/ folder; "
            f"`launchkit interface list` shows them)"
        ) from None


def get_service(name: str) -> type[ServiceType]:
    """The service type (with ``.Request``/``.Response``/``.Event``) for ``pkg/srv/Name``."""
    full = normalize_type_name(name, "srv")
    try:
        return registry().service_class(full)
    except (KeyError, ValueError):
        raise MessageTypeError(
            f"unknown service type {name!r} (expected one of: {', '.join(type_names('srv'))}, "
            "or one of a package's srv/ folder)"
        ) from None


def get_action(name: str) -> type[ActionType]:
    """The action type (``.Goal``, ``.Result``, ``.Feedback``, ``.Impl``) for
    ``pkg/action/Name``."""
    full = normalize_type_name(name, "action")
    try:
        return registry().action_class(full)
    except (KeyError, ValueError):
        raise MessageTypeError(
            f"unknown action type {name!r} (expected an action of a package's action/ folder, "
            "e.g. example_interfaces/action/Fibonacci)"
        ) from None


def is_message(value: Any) -> bool:
    """Whether ``value`` is a message (an instance of a launchkit message class)."""
    return isinstance(type(value), MessageMeta)


def message_type_name(msg_or_cls: Any) -> str:
    """``pkg/msg/Name`` of a message instance or class (``pkg/srv/Name`` of a service type,
    ``pkg/action/Name`` of an action type)."""
    name = getattr(msg_or_cls, "_TYPE_NAME", None)
    if not isinstance(name, str):
        raise MessageTypeError(f"{msg_or_cls!r} is not a ROS message, service or action type")
    return name


def message_spec(type_name: str) -> MessageSpec:
    """The constants and fields of a message type (rosbags' field descriptions)."""
    try:
        return registry().spec(type_name)
    except (KeyError, ValueError):
        raise MessageTypeError(f"unknown message type {type_name!r}") from None


def codec(type_name: str) -> Codec:
    """The codec of message type ``type_name`` (``pkg/msg/Name``)."""
    try:
        return registry().codec(type_name)
    except (KeyError, ValueError):
        raise MessageTypeError(f"unknown message type {type_name!r}") from None


def serialize(msg: Any, type_name: str | None = None) -> bytes:
    """CDR bytes (little endian, with the 4-byte encapsulation header) of a message."""
    return bytes(codec(type_name or message_type_name(msg)).serialize(msg))


def deserialize(data: bytes | memoryview, type_name: str) -> Any:
    """Decode CDR bytes (with header) into a message of ``type_name`` (``pkg/msg/Name``)."""
    return codec(type_name).deserialize(data)


def type_hash(type_name: str) -> str:
    """The RIHS01 hash string of ``pkg/msg/Name``, ``pkg/srv/Name`` or ``pkg/action/Name``."""
    try:
        return registry().type_hash(type_name)
    except (KeyError, ValueError):
        raise MessageTypeError(f"unknown type {type_name!r}") from None


def message_definition(type_name: str) -> str:
    """The ``.msg`` text of a type with its dependencies (as MCAP/Foxglove ``ros2msg`` want)."""
    return registry().message_definition(type_name)


def register_types(typesdict: dict[str, Any]) -> None:
    """Add message types from rosbags' ``{name: (constants, fields)}`` (a bag's definitions,
    from ``rosbags.typesys.get_types_from_msg``); known types keep theirs."""
    registry().register(typesdict)
