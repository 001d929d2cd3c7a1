"""A message type's fields as the page builds forms from them (the service caller and the topic
publisher): names, ROS types, nesting, array lengths and the type's constants, from the type
store, so the page needs no ``.msg`` parser.

A field is ``{"name", "kind", ...}`` with ``kind`` one of ``base`` (``type``: ``float64``,
``string``, ...), ``message`` (``type`` and its ``fields``), ``array`` (fixed ``length``) and
``sequence`` (``bound``, 0 for none); the last two describe their elements in ``item``.
"""

from __future__ import annotations

import functools
from typing import Any

from launchkit.ros.message_data import constants_of, fields_of

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4


@functools.cache
def message_schema(type_name: str) -> dict[str, Any]:
    """``{"type", "fields", "constants"}`` of a message type (``KeyError`` when unknown)."""
    return {
        "type": type_name,
        "fields": [{"name": name, **_field(desc)} for name, desc in fields_of(type_name)],
        "constants": [
            {"name": name, "type": base, "value": value}
            for name, base, value in constants_of(type_name)
        ],
    }


def _field(desc: Any) -> dict[str, Any]:
    kind, detail = desc
    if kind == _BASE:
        return {"kind": "base", "type": detail[0]}
    if kind == _NAME:
        nested = message_schema(detail)
        return {"kind": "message", "type": detail, "fields": nested["fields"]}
    item, size = detail
    if kind == _ARRAY:
        return {"kind": "array", "length": size, "item": _field(item)}
    return {"kind": "sequence", "bound": size, "item": _field(item)}


def interface_schema(type_name: str) -> dict[str, Any]:
    """A message type's schema as ``{"message": ...}``, a service type's as ``{"request": ...,
    "response": ...}`` (``KeyError`` when the type is unknown)."""
    if "/srv/" in type_name:
        return {
            "request": message_schema(type_name + "_Request"),
            "response": message_schema(type_name + "_Response"),
        }
    return {"message": message_schema(type_name)}
