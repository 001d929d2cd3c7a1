"""Messages to and from plain data and YAML, as ``ros2 topic echo`` / ``topic pub`` do (and as
the viewer sends them to its page): rosidl_runtime_py's ``convert`` and ``set_message``."""

from __future__ import annotations

import array
from typing import Any

import numpy as np
import yaml

from launchkit.errors import UserError
from launchkit.ros.msgs import get_message, is_message, message_spec, message_type_name

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
_INTS = {"byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"}
TRUNCATE_LENGTH = 128


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


def to_data(msg: Any, truncate: int | None = TRUNCATE_LENGTH) -> dict[str, Any]:
    """A message as nested dicts/lists (long strings and arrays cut like ``ros2 topic echo``)."""
    out: dict[str, Any] = {}
    for name, _ in fields_of(message_type_name(msg)):
        out[name] = _value(getattr(msg, name), truncate)
    return out


def _value(value: Any, truncate: int | None) -> Any:
    if is_message(value):
        return to_data(value, truncate)
    if isinstance(value, (np.ndarray, array.array)):
        value = value.tolist()
    if isinstance(value, list):
        items = [_value(v, truncate) for v in value]
        if truncate is not None and len(items) > truncate:
            return [*items[:truncate], "..."]
        return items
    if isinstance(value, str) and truncate is not None and len(value) > truncate:
        return value[:truncate] + "..."
    return value


def to_yaml(msg: Any, truncate: int | None = TRUNCATE_LENGTH) -> str:
    """A message as block YAML, like ``ros2 topic echo``."""
    return yaml.safe_dump(
        to_data(msg, truncate), default_flow_style=False, sort_keys=False, width=1 << 30
    )


def from_yaml(type_name: str, text: str) -> Any:
    """Build a message of ``type_name`` from YAML text (``'{linear: {x: 1.0}}'``)."""
    try:
        data = yaml.safe_load(text) if text.strip() else {}
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise MessageValueError(
            f"the values {text!r} are not valid YAML ({mark})",
            expected=f"a YAML mapping of {type_name} fields, e.g. '{{{_example(type_name)}}}'",
        ) from None
    if data is None:
        data = {}
    return build(type_name, data, type_name)


def build(type_name: str, data: Any, path: str) -> Any:
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
        kwargs[key] = _convert(fields[key], value, f"{path}.{key}")
    return cls(**kwargs)


def _convert(desc: Any, value: Any, path: str) -> Any:
    kind, detail = desc
    if kind == _BASE:
        return _base(detail[0], value, path)
    if kind == _NAME:
        return build(detail, value, path)
    sub, length = detail
    if not isinstance(value, list):
        raise MessageValueError(f"{path}: got {value!r}, expected a list")
    if kind == _ARRAY and len(value) != length:
        raise MessageValueError(f"{path}: got {len(value)} items, expected exactly {length}")
    if kind == _SEQUENCE and length and len(value) > length:
        raise MessageValueError(f"{path}: got {len(value)} items, expected at most {length}")
    return [_convert(sub, v, f"{path}[{i}]") for i, v in enumerate(value)]


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


def short_repr(msg: Any) -> str:
    """``pkg.msg.Name(field=value, ...)``, the form ``ros2 service call`` prints."""
    type_name = message_type_name(msg)
    parts = []
    for name, _ in fields_of(type_name):
        value = getattr(msg, name)
        if is_message(value):
            text = short_repr(value)
        elif isinstance(value, list) and value and is_message(value[0]):
            text = "[" + ", ".join(short_repr(v) for v in value) + "]"
        else:
            text = repr(_value(value, None))
        parts.append(f"{name}={text}")
    return f"{type_name.replace('/', '.')}({', '.join(parts)})"
