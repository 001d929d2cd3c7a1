"""What one message type is: its constants and fields, as the rest of the package reads them.

A field keeps rosbags' field description (``(1, ('float64', 0))``, ``(2, 'std_msgs/msg/Header')``,
``(3, (inner, N))`` arrays, ``(4, (inner, N))`` sequences: what rosbags' parser and its Jazzy
store produce, and what its RIHS01 hash reads) plus the ``.msg`` default value rosbags does not
keep. Everything else (rosidl's IDL types, field type strings, numpy dtypes and ``array`` type
codes) is derived here, once per field.

``char`` is rewritten to ``uint8`` when a spec is made, as rosidl_adapter does for ``.msg`` files:
rosidl's classes, hashes and bytes all see a ``uint8``.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from typing import Any, NamedTuple

from launchkit.ros.msgs import definition as d

BASE, NAME, ARRAY, SEQUENCE = 1, 2, 3, 4  # rosbags' Nodetype values

#: ``.msg`` base type -> IDL type name (rosidl_adapter's mapping).
IDL_NAMES = {
    "bool": "boolean",
    "byte": "octet",
    "char": "uint8",
    "float32": "float",
    "float64": "double",
    **{name: name for name in d.INTEGER_TYPES},
}

#: IDL types held in ``array.array`` (sequences) and ``numpy.ndarray`` (fixed arrays), with
#: their type codes (dtypes: :func:`dtype_code`): rosidl_generator_py's SPECIAL_NESTED_BASIC_TYPES.
TYPE_CODES = {
    "float": "f",
    "double": "d",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
}


def item_size(special: str) -> int:
    """Bytes per element of a numeric array or sequence of IDL type ``special``."""
    return struct.calcsize("<" + TYPE_CODES[special])


def dtype_code(special: str) -> str:
    """numpy's dtype of ``special`` without its byte order: ``"f8"``, ``"u1"``, ``"i4"``."""
    kind = "f" if special in ("float", "double") else "u" if special.startswith("u") else "i"
    return f"{kind}{item_size(special)}"


class Constant(NamedTuple):
    """A constant: its name, ``.msg`` base type (``char`` already ``uint8``) and value."""

    name: str
    base: str
    value: Any


class Field(NamedTuple):
    """A field: name, rosbags description, and the ``.msg`` default (``has_default``)."""

    name: str
    desc: Any
    default: Any = None
    has_default: bool = False


class MessageSpec(NamedTuple):
    """A message type ``pkg/msg/Name`` (or ``pkg/srv/Name_Request``, ``pkg/action/Name_Goal``)."""

    name: str
    constants: tuple[Constant, ...]
    fields: tuple[Field, ...]

    def typesdict_entry(self) -> tuple[list[tuple[str, str, Any]], list[tuple[str, Any]]]:
        """``(constants, fields)`` as rosbags' ``Typestore.fielddefs`` holds them."""
        return (
            [(c.name, c.base, c.value) for c in self.constants],
            [(f.name, f.desc) for f in self.fields],
        )


def spec_from_typesdict(
    name: str, entry: Any, defaults: dict[str, Any] | None = None
) -> MessageSpec:
    """A spec from rosbags' ``(constants, fields)`` of ``name``, with ``.msg`` defaults."""
    consts, fields = entry
    defaults = defaults or {}
    return MessageSpec(
        name,
        tuple(Constant(c[0], uint8_for_char(c[1]), c[2]) for c in consts),
        tuple(
            Field(fname, desc_without_char(desc), defaults.get(fname), fname in defaults)
            for fname, desc in fields
        ),
    )


def uint8_for_char(base: str) -> str:
    """``uint8`` for ``char``, else ``base``."""
    return "uint8" if base == "char" else base


def desc_without_char(desc: Any) -> Any:
    """``desc`` with ``char`` rewritten to ``uint8`` (at any depth)."""
    kind, detail = desc
    if kind == BASE and detail[0] == "char":
        return (BASE, ("uint8", detail[1]))
    if kind in (ARRAY, SEQUENCE):
        return (kind, (desc_without_char(detail[0]), detail[1]))
    return desc


def desc_renamed(desc: Any, rename: Callable[[str], str]) -> Any:
    """``desc`` with every message type name passed through ``rename``."""
    kind, detail = desc
    if kind == NAME:
        return (NAME, rename(detail))
    if kind in (ARRAY, SEQUENCE):
        return (kind, (desc_renamed(detail[0], rename), detail[1]))
    return desc


def element_desc(desc: Any) -> Any:
    """The description of an array's or sequence's elements (``desc`` itself for scalars)."""
    return desc[1][0] if desc[0] in (ARRAY, SEQUENCE) else desc


def referenced_types(spec: MessageSpec) -> list[str]:
    """The message types ``spec``'s fields use, in field order."""
    found = []
    for field in spec.fields:
        inner = element_desc(field.desc)
        if inner[0] == NAME:
            found.append(inner[1])
    return found


def idl_type(desc: Any) -> d.AbstractType:
    """The rosidl type of a field description (what ``SLOT_TYPES`` holds)."""
    kind, detail = desc
    if kind == BASE:
        base, bound = detail
        if base == "string":
            return d.BoundedString(bound) if bound else d.UnboundedString()
        return d.BasicType(IDL_NAMES[base])
    if kind == NAME:
        pkg, sub, short = detail.split("/")
        return d.NamespacedType([pkg, sub], short)
    inner = idl_type(detail[0])
    assert isinstance(inner, d.AbstractNestableType)
    if kind == ARRAY:
        return d.Array(inner, detail[1])
    return d.BoundedSequence(inner, detail[1]) if detail[1] else d.UnboundedSequence(inner)


def field_type_string(idl: d.AbstractType) -> str:
    """The type as ``get_fields_and_field_types()`` writes it: ``double``, ``string<5>``,
    ``std_msgs/Header``, ``sequence<uint8>``, ``sequence<int32, 3>``, ``double[9]``."""
    inner = idl.value_type if isinstance(idl, d.AbstractNestedType) else idl
    if isinstance(inner, d.BasicType):
        text = inner.typename
    elif isinstance(inner, d.BoundedString):
        text = f"string<{inner.maximum_size}>"
    elif isinstance(inner, d.UnboundedString):
        text = "string"
    else:
        assert isinstance(inner, d.NamespacedType)
        text = f"{inner.namespaces[0]}/{inner.name}"
    if isinstance(idl, d.BoundedSequence):
        return f"sequence<{text}, {idl.maximum_size}>"
    if isinstance(idl, d.UnboundedSequence):
        return f"sequence<{text}>"
    if isinstance(idl, d.Array):
        return f"{text}[{idl.size}]"
    return text


def python_type_name(idl: d.AbstractType) -> str:
    """The Python type rosidl checks elements or values against: ``int``, ``float``, ``bool``,
    ``bytes``, ``str`` or the message class name."""
    if isinstance(idl, d.NamespacedType):
        return idl.name
    if isinstance(idl, d.AbstractGenericString):
        return "str"
    assert isinstance(idl, d.BasicType)
    if idl.typename == d.BOOLEAN_TYPE:
        return "bool"
    if idl.typename == d.OCTET_TYPE:
        return "bytes"
    if idl.typename in d.INTEGER_TYPES:
        return "int"
    return "float"


def special_typename(idl: d.AbstractType) -> str | None:
    """The element IDL type name when ``idl`` is an array or sequence rosidl keeps in numpy or
    ``array.array`` (numbers), else None."""
    if isinstance(idl, d.AbstractNestedType) and isinstance(idl.value_type, d.BasicType):
        name = idl.value_type.typename
        return name if name in TYPE_CODES else None
    return None


SERVICE_SUFFIXES = ("_Request", "_Response", "_Event")
#: The suffixes of an action's types, longest first (so ``_SendGoal_Request`` wins over ``_Goal``).
ACTION_SUFFIXES = (
    "_SendGoal_Request",
    "_SendGoal_Response",
    "_SendGoal_Event",
    "_GetResult_Request",
    "_GetResult_Response",
    "_GetResult_Event",
    "_FeedbackMessage",
    "_SendGoal",
    "_GetResult",
    "_Feedback",
    "_Result",
    "_Goal",
)
