"""``launchkit interface show|list``: message and service definitions."""

from __future__ import annotations

import argparse
from typing import Any

from launchkit.ros.message_data import constants_of, fields_of
from launchkit.ros.msgs import (
    MessageTypeError,
    get_action,
    get_message,
    get_service,
    normalize_type_name,
    type_names,
)

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
# the member rosidl gives an empty message (std_srvs/srv/Trigger's request); not in its .msg
_PLACEHOLDER = "structure_needs_at_least_one_member"


def add_parser(commands: Any) -> None:
    """Register the ``interface`` subcommands."""
    interface = commands.add_parser(
        "interface", help="message, service and action types: show, list"
    )
    sub = interface.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("show", help="print a type's definition")
    p.add_argument(
        "type_name",
        help="e.g. geometry_msgs/msg/Twist, std_srvs/srv/Trigger or "
        "example_interfaces/action/Fibonacci",
    )
    p.set_defaults(run=_show)
    p = sub.add_parser("list", help="list every known type")
    p.set_defaults(run=_list)


def _list(args: argparse.Namespace) -> int:
    for kind, title in (("msg", "Messages"), ("srv", "Services"), ("action", "Actions")):
        print(f"{title}:")
        for name in type_names(kind, discover=True):
            print(f"    {name}")
    return 0


def _show(args: argparse.Namespace) -> int:
    text = args.type_name
    if "/action/" in text.replace("::", "/"):
        action = get_action(text)
        for part in ("_Goal", "_Result", "_Feedback"):
            if part != "_Goal":
                print("---")
            _print_lines(definition(action._TYPE_NAME + part))
        return 0
    if "/srv/" in text.replace("::", "/"):
        srv = get_service(text)
        _print_lines(definition(srv._TYPE_NAME + "_Request"))
        print("---")
        _print_lines(definition(srv._TYPE_NAME + "_Response"))
        return 0
    try:
        cls = get_message(text)
    except MessageTypeError:
        if "/" in text and text.count("/") == 1:  # pkg/Name may be a service
            try:
                srv = get_service(normalize_type_name(text, "srv"))
            except MessageTypeError:
                raise MessageTypeError(
                    f"unknown interface {text!r}",
                    expected="a type such as geometry_msgs/msg/Twist (`launchkit interface list`)",
                ) from None
            args.type_name = srv._TYPE_NAME
            return _show(args)
        raise
    _print_lines(definition(cls._TYPE_NAME))
    return 0


def _print_lines(lines: list[str]) -> None:
    for line in lines:
        print(line)


def definition(type_name: str, indent: str = "") -> list[str]:
    """The lines ``ros2 interface show`` prints: fields, nested types indented by a tab."""
    lines = [f"{indent}{base} {name}={value}" for name, base, value in constants_of(type_name)]
    for name, desc in fields_of(type_name):
        if name == _PLACEHOLDER:
            continue
        lines.append(f"{indent}{_type_text(desc)} {name}")
        nested = _nested(desc)
        if nested is not None:
            lines.extend(definition(nested, indent + "\t"))
    return lines


def _nested(desc: Any) -> str | None:
    kind, detail = desc
    if kind == _NAME:
        return str(detail)
    if kind in (_ARRAY, _SEQUENCE):
        return _nested(detail[0])
    return None


def _type_text(desc: Any) -> str:
    kind, detail = desc
    if kind == _BASE:
        base, bound = detail
        return f"{base}<={bound}" if bound else str(base)
    if kind == _NAME:
        return str(detail).rsplit("/", 1)[-1] + " "
    inner = _type_text(detail[0]).rstrip()
    if kind == _ARRAY:
        return f"{inner}[{detail[1]}]"
    return f"{inner}[<={detail[1]}]" if detail[1] else f"{inner}[]"
