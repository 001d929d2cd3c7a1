"""``.msg``, ``.srv`` and ``.action`` text to message specs, as rosidl reads them.

Each line of a ``.msg`` is read by rosbags' parser (``MSGParser``, the parser behind
``get_types_from_msg``), one line at a time so that every field and constant knows its line:
a mistake is reported as ``FILE:LINE:COL: error: ...``. rosbags keeps the default values that
``get_types_from_msg`` drops, so they are read from its parse tree. A ``.srv`` splits on its one
``---`` line into ``Name_Request`` and ``Name_Response`` (plus rosidl's ``Name_Event``); an
``.action`` on its two into ``Name_Goal``, ``Name_Result`` and ``Name_Feedback``, expanded as
rosidl does into the ``Name_SendGoal`` and ``Name_GetResult`` services and
``Name_FeedbackMessage``. For hashing, the service and action themselves are described as
rosidl_generator_type_description does: a service by its request, response and event messages,
an action by its six parts.
"""

from __future__ import annotations

import re
from itertools import pairwise
from typing import Any, NamedTuple

from rosbags.typesys.base import Field as ParsedField
from rosbags.typesys.base import NamedType, TypesysError, create_field_desc
from rosbags.typesys.msg import MSGParser

from launchkit.errors import Location, UserError
from launchkit.ros.msgs import _spec as s

# rosidl_adapter's rules for names
_FIELD_NAME = re.compile(r"^(?!.*__)(?!.*_$)[a-z][a-z0-9_]*$")
_CONSTANT_NAME = re.compile(r"^[A-Z]([A-Z0-9_]?[A-Z0-9]+)*$")
_TYPE_NAME = re.compile(r"^[A-Z][A-Za-z0-9]*$")
_SEPARATOR = "---"
_INT_RANGES = {
    **{f"int{bits}": (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1) for bits in (8, 16, 32, 64)},
    **{f"uint{bits}": (0, 2**bits - 1) for bits in (8, 16, 32, 64)},
    "byte": (0, 255),
    "char": (0, 255),
}

UUID = "unique_identifier_msgs/msg/UUID"
TIME = "builtin_interfaces/msg/Time"
EVENT_INFO = "service_msgs/msg/ServiceEventInfo"


class InterfaceFileError(UserError):
    """An interface file (``.msg``, ``.srv``, ``.action``) that rosidl would not accept."""


class Reference(NamedTuple):
    """A message type a field uses, and where."""

    type_name: str
    location: Location


class Parsed(NamedTuple):
    """The message specs an interface file defines and the types its fields use."""

    specs: dict[str, s.MessageSpec]
    references: list[Reference]


def parse_interface(text: str, type_name: str, path: str) -> Parsed:
    """The specs of ``pkg/msg/Name``, ``pkg/srv/Name`` or ``pkg/action/Name`` from its text."""
    _, kind, short = type_name.split("/")
    if not _TYPE_NAME.match(short):
        raise InterfaceFileError(
            f"interface name {short!r} is not allowed",
            Location(path, 1, 1),
            expected="an UpperCamelCase name of letters and digits, e.g. AddTwoInts",
        )
    parts = _split(text, path, 1 if kind == "srv" else 2 if kind == "action" else 0)
    if kind == "msg":
        return parse_message(text, type_name, path)
    if kind == "srv":
        return _service(type_name, parts, path)
    return _action(type_name, parts, path)


def parse_message(text: str, type_name: str, path: str, first_line: int = 1) -> Parsed:
    """The spec of one message from ``.msg`` text (``first_line``: the text's line in ``path``)."""
    constants: list[s.Constant] = []
    fields: list[s.Field] = []
    references: list[Reference] = []
    names: dict[str, int] = {}
    # parsed as a msg of the package, so that a bare "Name" means pkg/msg/Name as in rosidl
    pkg, _, short = type_name.split("/")
    for offset, line in enumerate(text.split("\n")):
        where = Location(path, first_line + offset, 1)
        try:
            (parsed,) = MSGParser(f"MSG: {pkg}/msg/{short}\n{line}\n").specification()
        except TypesysError:
            raise InterfaceFileError(
                f"cannot read {line.strip()!r}",
                where,
                expected="a field 'TYPE name [DEFAULT]', a constant 'TYPE NAME=VALUE' or a comment",
            ) from None
        for constant in parsed.constants:
            constants.append(_constant(constant.typ.value, constant.name, constant.value, where))
            _unique(constant.name, names, where)
        for field in parsed.fields:
            made = _field(field, line, where)
            fields.append(made)
            _unique(made.name, names, where)
            inner = s.element_desc(made.desc)
            if inner[0] == s.NAME:
                indent = len(line) - len(line.lstrip())
                references.append(Reference(inner[1], where.shifted(indent)))
    if not fields:
        fields.append(s.Field("structure_needs_at_least_one_member", (s.BASE, ("uint8", 0))))
    return Parsed(
        {type_name: s.MessageSpec(type_name, tuple(constants), tuple(fields))}, references
    )


def _unique(name: str, seen: dict[str, int], where: Location) -> None:
    if name in seen:
        raise InterfaceFileError(
            f"{name!r} is defined twice (first on line {seen[name]})",
            where,
            expected="each field and constant name once",
        )
    seen[name] = where.line


def _constant(base: str, name: str, value: Any, where: Location) -> s.Constant:
    if not _CONSTANT_NAME.match(name):
        raise InterfaceFileError(
            f"constant name {name!r} is not allowed", where, expected="an UPPER_CASE name"
        )
    return s.Constant(name, s.uint8_for_char(base), _literal(base, 0, value, where))


def _field(field: ParsedField, line: str, where: Location) -> s.Field:
    if not _FIELD_NAME.match(field.name):
        raise InterfaceFileError(
            f"field name {field.name!r} is not allowed",
            where,
            expected="a lower_case name (letters, digits, single underscores, no trailing '_')",
        )
    if isinstance(field.typ.ref, NamedType) and field.typ.ref.name.endswith(("/wstring", "/wchar")):
        raise InterfaceFileError(
            f"field {field.name!r}: wide strings are not supported by launchkit",
            where,
            expected="string",
        )
    desc = s.desc_without_char(create_field_desc(field.typ))
    if field.value is None:
        return s.Field(field.name, desc)
    base = s.element_desc(create_field_desc(field.typ))
    if base[0] != s.BASE:
        raise InterfaceFileError(
            f"field {field.name!r}: a message-typed field cannot have a default value", where
        )
    default = _default(desc, base[1], field.value, _quote_of(line, field.name), where)
    return s.Field(field.name, desc, default, True)


def _quote_of(line: str, name: str) -> str | None:
    """The quote character around a string default in ``line`` (rosidl unescapes only it)."""
    found = re.search(rf"\s{re.escape(name)}\s+(['\"])", line)
    return found.group(1) if found else None


def _default(
    desc: Any, base: tuple[str, int], value: Any, quote: str | None, where: Location
) -> Any:
    kind, detail = desc
    if kind == s.BASE:
        return _literal(base[0], base[1], value, where, quote)
    if not isinstance(value, list):
        raise InterfaceFileError(f"default {value!r} is not a list", where, expected="[a, b, ...]")
    size = detail[1]
    if kind == s.ARRAY and len(value) != size:
        raise InterfaceFileError(
            f"default has {len(value)} values", where, expected=f"exactly {size}"
        )
    if kind == s.SEQUENCE and size and len(value) > size:
        raise InterfaceFileError(
            f"default has {len(value)} values", where, expected=f"at most {size}"
        )
    return [_literal(base[0], base[1], item, where, quote) for item in value]


def _literal(base: str, bound: int, value: Any, where: Location, quote: str | None = None) -> Any:
    """A constant or default value checked against its type, as rosidl_adapter checks it."""
    if base == "string":
        text = value if isinstance(value, str) else str(value)
        if quote is not None:
            text = text.replace("\\" + quote, quote)
        if bound and len(text) > bound:
            raise InterfaceFileError(
                f"string {text!r} is longer than {bound}",
                where,
                expected=f"at most {bound} characters",
            )
        return text
    if base == "bool":
        if isinstance(value, bool) or value in (0, 1):
            return bool(value)
        raise InterfaceFileError(f"{value!r} is not a bool", where, expected="true/false or 1/0")
    if base in ("float32", "float64"):
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        raise InterfaceFileError(f"{value!r} is not a number", where, expected=f"a {base} value")
    low, high = _INT_RANGES[base]
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise InterfaceFileError(
            f"{value!r} is not a valid {base} value",
            where,
            expected=f"an integer in [{low}, {high}]",
        )
    return value


def _split(text: str, path: str, separators: int) -> list[tuple[str, int]]:
    """``text`` split at its ``---`` lines: (part, its first line number)."""
    lines = text.split("\n")
    at = [i for i, line in enumerate(lines) if line.rstrip("\r") == _SEPARATOR]
    if len(at) != separators:
        what = {0: "a message", 1: "a service", 2: "an action"}[separators]
        line = at[separators] + 1 if len(at) > separators else 1
        raise InterfaceFileError(
            f"{len(at)} '---' separator lines in {what}",
            Location(path, line, 1),
            expected=f"exactly {separators}"
            + {0: "", 1: " (request --- response)", 2: " (goal --- result --- feedback)"}[
                separators
            ],
        )
    bounds = [-1, *at, len(lines)]
    return [("\n".join(lines[a + 1 : b]), a + 2) for a, b in pairwise(bounds)]


def _service(type_name: str, parts: list[tuple[str, int]], path: str) -> Parsed:
    (request, request_line), (response, response_line) = parts
    specs: dict[str, s.MessageSpec] = {}
    references: list[Reference] = []
    for suffix, (text, line) in (
        ("_Request", (request, request_line)),
        ("_Response", (response, response_line)),
    ):
        parsed = parse_message(text, type_name + suffix, path, line)
        specs.update(parsed.specs)
        references.extend(parsed.references)
    specs.update(service_wrappers(type_name))
    return Parsed(specs, references)


def service_wrappers(type_name: str) -> dict[str, s.MessageSpec]:
    """rosidl's ``Name_Event`` message of service ``type_name`` and the service's description
    (its request, response and event, which its RIHS01 hash is of)."""
    return {
        type_name + "_Event": _struct(
            type_name + "_Event",
            ("info", (s.NAME, EVENT_INFO)),
            ("request", (s.SEQUENCE, ((s.NAME, type_name + "_Request"), 1))),
            ("response", (s.SEQUENCE, ((s.NAME, type_name + "_Response"), 1))),
        ),
        type_name: _struct(
            type_name,
            ("request_message", (s.NAME, type_name + "_Request")),
            ("response_message", (s.NAME, type_name + "_Response")),
            ("event_message", (s.NAME, type_name + "_Event")),
        ),
    }


def _action(type_name: str, parts: list[tuple[str, int]], path: str) -> Parsed:
    specs: dict[str, s.MessageSpec] = {}
    references: list[Reference] = []
    for suffix, (text, line) in zip(("_Goal", "_Result", "_Feedback"), parts, strict=True):
        parsed = parse_message(text, type_name + suffix, path, line)
        specs.update(parsed.specs)
        references.extend(parsed.references)
    send_goal, get_result = type_name + "_SendGoal", type_name + "_GetResult"
    specs.update(
        {
            send_goal + "_Request": _struct(
                send_goal + "_Request",
                ("goal_id", (s.NAME, UUID)),
                ("goal", (s.NAME, type_name + "_Goal")),
            ),
            send_goal + "_Response": _struct(
                send_goal + "_Response",
                ("accepted", (s.BASE, ("bool", 0))),
                ("stamp", (s.NAME, TIME)),
            ),
            get_result + "_Request": _struct(get_result + "_Request", ("goal_id", (s.NAME, UUID))),
            get_result + "_Response": _struct(
                get_result + "_Response",
                ("status", (s.BASE, ("int8", 0))),
                ("result", (s.NAME, type_name + "_Result")),
            ),
            type_name + "_FeedbackMessage": _struct(
                type_name + "_FeedbackMessage",
                ("goal_id", (s.NAME, UUID)),
                ("feedback", (s.NAME, type_name + "_Feedback")),
            ),
            **service_wrappers(send_goal),
            **service_wrappers(get_result),
            type_name: _struct(
                type_name,
                ("goal", (s.NAME, type_name + "_Goal")),
                ("result", (s.NAME, type_name + "_Result")),
                ("feedback", (s.NAME, type_name + "_Feedback")),
                ("send_goal_service", (s.NAME, send_goal)),
                ("get_result_service", (s.NAME, get_result)),
                ("feedback_message", (s.NAME, type_name + "_FeedbackMessage")),
            ),
        }
    )
    return Parsed(specs, references)


def _struct(name: str, *fields: tuple[str, Any]) -> s.MessageSpec:
    return s.MessageSpec(name, (), tuple(s.Field(fname, desc) for fname, desc in fields))
