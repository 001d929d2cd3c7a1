"""Lookup, CDR encoding and hashes of message and service types (by ``pkg/msg/Name``)."""

from __future__ import annotations

import functools
from typing import Any

from launchkit.errors import UserError
from launchkit.ros.msgs._codec import codec
from launchkit.ros.msgs._typestore import known_names, typestore_for


class MessageTypeError(UserError):
    """A message or service type name that does not exist (or is malformed)."""


class ServiceType:
    """A service type with its ``Request`` and ``Response`` message classes, like rclpy's."""

    Request: Any
    Response: Any
    Event: Any
    _TYPE_NAME: str

    def __init__(self) -> None:
        raise TypeError("a service type is not instantiated; use .Request() / .Response()")


def normalize_type_name(name: str, kind: str = "msg") -> str:
    """``pkg/Name`` or ``pkg/msg/Name`` (also ``pkg::msg::Name``) to ``pkg/<kind>/Name``."""
    parts = name.replace("::", "/").strip("/").split("/")
    if len(parts) == 2:
        parts = [parts[0], kind, parts[1]]
    if len(parts) != 3 or not all(parts):
        raise MessageTypeError(
            f"malformed {'service' if kind == 'srv' else 'message'} type {name!r} "
            f"(expected pkg/{kind}/Name, e.g. "
            f"{'std_srvs/srv/Trigger' if kind == 'srv' else 'geometry_msgs/msg/Twist'})"
        )
    return "/".join(parts)


def type_names(kind: str = "msg") -> list[str]:
    """Every known type name of a kind (``msg`` or ``srv``), sorted."""
    return sorted(known_names(kind))


def packages() -> set[str]:
    """Names of the packages that have message or service types."""
    return {name.split("/", 1)[0] for name in (*known_names("msg"), *known_names("srv"))}


def get_message(name: str) -> Any:
    """The message class for ``pkg/msg/Name`` (or ``pkg/Name``)."""
    full = normalize_type_name(name, "msg")
    try:
        return typestore_for(full).types[full]
    except KeyError:
        raise MessageTypeError(
            f"unknown message type {name!r} (expected a ROS 2 Jazzy type such as "
            f"std_msgs/msg/String; `launchkit interface list` shows them all)"
        ) from None


@functools.cache
def _service(full: str) -> type[ServiceType]:
    ts = typestore_for(full)
    short = full.rsplit("/", 1)[-1]
    return type(
        short,
        (ServiceType,),
        {
            "Request": ts.types[full + "_Request"],
            "Response": ts.types[full + "_Response"],
            "Event": ts.types[full + "_Event"],
            "_TYPE_NAME": full,
            "__doc__": f"The ROS 2 service type {full}.",
        },
    )


def get_service(name: str) -> type[ServiceType]:
    """The service type (with ``.Request``/``.Response``) for ``pkg/srv/Name``."""
    full = normalize_type_name(name, "srv")
    if full + "_Request" not in typestore_for(full).types:
        raise MessageTypeError(
            f"unknown service type {name!r} (expected one of: {', '.join(type_names('srv'))})"
        )
    return _service(full)


def message_type_name(msg_or_cls: Any) -> str:
    """``pkg/msg/Name`` of a message instance or class (``pkg/srv/Name`` of a service type)."""
    name = getattr(msg_or_cls, "_TYPE_NAME", None) or getattr(msg_or_cls, "__msgtype__", None)
    if not isinstance(name, str):
        raise MessageTypeError(f"{msg_or_cls!r} is not a ROS message or service type")
    return name


def serialize(msg: Any, type_name: str | None = None) -> bytes:
    """CDR bytes (little endian, with the 4-byte encapsulation header) of a message."""
    return bytes(codec(type_name or msg.__msgtype__).serialize(msg))


def deserialize(data: bytes | memoryview, type_name: str) -> Any:
    """Decode CDR bytes (with header) into a message of ``type_name`` (``pkg/msg/Name``)."""
    return codec(type_name).deserialize(data)


def type_hash(type_name: str) -> str:
    """The RIHS01 hash string of ``pkg/msg/Name`` or ``pkg/srv/Name``."""
    return _hash(type_name)


@functools.cache
def _hash(type_name: str) -> str:
    return str(typestore_for(type_name).hash_rihs01(type_name))


def message_definition(type_name: str) -> str:
    """The ``.msg`` text of a type with its dependencies (as MCAP/Foxglove ``ros2msg`` want)."""
    ts = typestore_for(type_name)
    text, _ = ts.generate_msgdef(type_name, ros_version=2)
    return str(text)
