"""Messages built from plain data and YAML, as ``ros2 topic pub`` and ``ros2 service call`` build
them (rosidl_runtime_py's ``set_message_fields``, with a located error for each mistake), and the
field descriptions of a type. The other direction, messages as text, is
:mod:`launchkit.ros.message_text`."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import yaml

from launchkit.errors import UserError
from launchkit.ros.msgs import get_message, message_spec

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
_INTS = {"byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"}


class MessageValueError(UserError):
    """YAML that does not fit a message type."""


def fields_of(type_name: str) -> list[tuple[str, Any]]:
    """(field name, rosbags field description) of a message type, in order."""
    return [
        (field.name, field.desc)
        for field in message_spec(type_name).fields
        if field.name != "structure_needs_at_least_one_member"
    ]


def constants_of(type_name: str) -> list[tuple[str, str, Any]]:
    """(name, base type, value) of a message type's constants."""
    return [(c.name, c.base, c.value) for c in message_spec(type_name).constants]


#: what builds a ``builtin_interfaces/msg/Time`` of the current time (``'now'`` and a header's
#: ``'auto'``, as ``ros2 topic pub`` expands them)
Now = Callable[[], Any]
_HEADER, _TIME = "std_msgs/msg/Header", "builtin_interfaces/msg/Time"


def from_yaml(type_name: str, text: str, now: Now | None = None) -> Any:
    """Build a message of ``type_name`` from YAML text (``'{linear: {x: 1.0}}'``); with ``now``,
    a ``Time`` field given as ``now`` and a ``Header`` given as ``auto`` get the current time."""
    return build(type_name, parse_values(type_name, text), type_name, now)


def parse_values(type_name: str, text: str) -> Any:
    """The YAML text of a message's values, read (not yet checked against ``type_name``)."""
    try:
        data = yaml.safe_load(text) if text.strip() else {}
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise MessageValueError(
            f"the values {text!r} are not valid YAML ({mark})",
            expected=f"a YAML mapping of {type_name} fields, e.g. '{{{_example(type_name)}}}'",
        ) from None
    return {} if data is None else data


def mentions_now(data: Any) -> bool:
    """Whether parsed values ask for the current time somewhere (``now`` or ``auto``), so a
    message built from them differs each time it is built."""
    if isinstance(data, dict):
        return any(mentions_now(v) for v in data.values())
    if isinstance(data, list):
        return any(mentions_now(v) for v in data)
    return data in ("now", "auto")


def build(type_name: str, data: Any, path: str, now: Now | None = None) -> Any:
    """A message of ``type_name`` with the fields in the mapping ``data`` set (checked)."""
    cls = get_message(type_name)
    if not isinstance(data, dict):
        raise MessageValueError(
            f"{path}: got {data!r}, expected a mapping of {type_name} fields "
            f"({', '.join(n for n, _ in fields_of(type_name)) or 'none'})"
        )
    fields = dict(fields_of(type_name))
    kwargs: dict[str, Any] = {}
    for key, value in data.items():
        if key not in fields:
            raise MessageValueError(
                f"{path}: {type_name} has no field {key!r}",
                expected="one of: " + ", ".join(fields) if fields else "no fields",
            )
        kwargs[key] = _convert(fields[key], value, f"{path}.{key}", now)
    return cls(**kwargs)


def _convert(desc: Any, value: Any, path: str, now: Now | None) -> Any:
    kind, detail = desc
    if kind == _BASE:
        return _base(detail[0], value, path)
    if kind == _NAME:
        if now is not None and detail == _TIME and value == "now":
            return now()
        if now is not None and detail == _HEADER and value == "auto":
            return get_message(_HEADER)(stamp=now())
        return build(detail, value, path, now)
    sub, length = detail
    if not isinstance(value, list):
        raise MessageValueError(f"{path}: got {value!r}, expected a list")
    if kind == _ARRAY and len(value) != length:
        raise MessageValueError(f"{path}: got {len(value)} items, expected exactly {length}")
    if kind == _SEQUENCE and length and len(value) > length:
        raise MessageValueError(f"{path}: got {len(value)} items, expected at most {length}")
    return [_convert(sub, v, f"{path}[{i}]", now) for i, v in enumerate(value)]


def _base(base: str, value: Any, path: str) -> Any:
    if base in ("string", "wstring"):
        if isinstance(value, (dict, list)):
            raise MessageValueError(f"{path}: got {value!r}, expected a string")
        return "" if value is None else str(value)
    if base == "bool":
        if not isinstance(value, bool):
            raise MessageValueError(f"{path}: got {value!r}, expected true or false")
        return value
    if base in ("float32", "float64"):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise MessageValueError(f"{path}: got {value!r}, expected a number")
        return float(value)
    if base in _INTS:
        if isinstance(value, bool) or not isinstance(value, int):
            raise MessageValueError(f"{path}: got {value!r}, expected an integer ({base})")
        return value
    raise MessageValueError(f"{path}: unsupported field type {base}")


def _example(type_name: str) -> str:
    fields = fields_of(type_name)
    if not fields:
        return ""
    name, (kind, detail) = fields[0]
    if kind == _NAME:
        return f"{name}: {{{_example(detail)}}}"
    if kind == _BASE:
        base = detail[0]
        sample = (
            "'text'"
            if base == "string"
            else "true"
            if base == "bool"
            else "1.0"
            if base.startswith("float")
            else "1"
        )
        return f"{name}: {sample}"
    return f"{name}: []"
