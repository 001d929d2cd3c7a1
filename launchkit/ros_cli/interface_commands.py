"""``launchkit interface list|show|package|packages|proto``: interface types as ``ros2
interface`` shows them.

A type is looked for first as a file of its package (what ``ros2 interface show`` prints, with
its comments), then in launchkit's type store (the built-in ROS 2 Jazzy types, whose text is
then rebuilt from their fields: no comments, one space between type and name).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from launchkit.packages import PackageIndex
from launchkit.ros.message_data import constants_of, fields_of
from launchkit.ros.msgs import MessageTypeError, get_message, packages, type_names
from launchkit.ros_cli.common import CliUsageError
from launchkit.ros_cli.interface_files import KINDS, SEPARATOR, file_lines, interface_file

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
# the member rosidl gives an empty message (std_srvs/srv/Trigger's request); not in its .msg
_PLACEHOLDER = "structure_needs_at_least_one_member"
#: the parts of a service's and an action's text, between ``---`` lines
_PARTS = {
    "msg": ("",),
    "srv": ("_Request", "_Response"),
    "action": ("_Goal", "_Result", "_Feedback"),
}
_TITLES = {"msg": "Messages", "srv": "Services", "action": "Actions"}


def add_parser(commands: Any) -> None:
    """Register the ``interface`` verbs."""
    interface = commands.add_parser(
        "interface", help="message, service and action types: list, show, package, packages, proto"
    )
    sub = interface.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="List all interface types available")
    _kind_options(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("show", help="Output the interface definition")
    comments = p.add_mutually_exclusive_group()
    comments.add_argument("--all-comments", action="store_true", help="nested types' too")
    comments.add_argument("--no-comments", action="store_true", help="no comments or blank lines")
    p.add_argument("type", help="e.g. geometry_msgs/msg/Twist; '-' reads it from stdin")
    p.set_defaults(run=_show)
    p = sub.add_parser("package", help="Output the interface types of one package")
    _kind_options(p)
    p.add_argument("package_name")
    p.set_defaults(run=_package)
    p = sub.add_parser("packages", help="Output the packages that provide interfaces")
    _kind_options(p)
    p.set_defaults(run=_packages)
    p = sub.add_parser("proto", help="Output an interface prototype (its default values)")
    p.add_argument("type")
    p.add_argument("--no-quotes", action="store_true", help="without the outer quotes")
    p.set_defaults(run=_proto)


def _kind_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-m", "--only-msgs", action="store_true", help="only message types")
    parser.add_argument("-s", "--only-srvs", action="store_true", help="only service types")
    parser.add_argument("-a", "--only-actions", action="store_true", help="only action types")


def _kinds(args: argparse.Namespace) -> list[str]:
    chosen = [
        kind
        for kind, flag in zip(
            KINDS, (args.only_msgs, args.only_srvs, args.only_actions), strict=True
        )
        if flag
    ]
    return chosen or list(KINDS)


def known_interfaces() -> dict[str, set[str]]:
    """``{kind: {pkg/kind/Name, ...}}``: the built-in types and those of every package's
    interface files (``ros2 interface list`` hides names with an ``_``: a service's or an
    action's parts are not listed either)."""
    return {kind: set(type_names(kind, discover=True)) for kind in KINDS}


def _list(args: argparse.Namespace) -> int:
    known = known_interfaces()
    for kind in _kinds(args):
        print(f"{_TITLES[kind]}:")
        for name in sorted(known[kind]):
            print(f"    {name}")
    return 0


def _packages(args: argparse.Namespace) -> int:
    known = known_interfaces()
    # one kind only, the first flag given, as ros2 interface packages takes them
    chosen = _kinds(args)[:1] if len(_kinds(args)) < len(KINDS) else list(KINDS)
    found = {name.split("/", 1)[0] for kind in chosen for name in known[kind]}
    for package in sorted(found):
        print(package)
    return 0


def _package(args: argparse.Namespace) -> int:
    index = PackageIndex()
    package = args.package_name
    known = known_interfaces()
    names = sorted(
        name for kind in _kinds(args) for name in known[kind] if name.split("/")[0] == package
    )
    if not names and package not in index.names() and package not in packages():
        raise CliUsageError(
            f"Unknown package '{package}'", expected="a package from `launchkit interface packages`"
        )
    for name in names:
        print(name)
    return 0


def _resolve(text: str, index: PackageIndex) -> str:
    """``pkg/kind/Name`` for what the user typed (``pkg/Name`` is looked for as each kind)."""
    parts = text.replace("::", "/").strip("/").split("/")
    if len(parts) == 3 and parts[1] in KINDS and all(parts):
        candidates = ["/".join(parts)]
    elif len(parts) == 2 and all(parts):
        candidates = [f"{parts[0]}/{kind}/{parts[1]}" for kind in KINDS]
    else:
        raise CliUsageError(
            f"Invalid name '{text}'", expected="pkg/msg/Name, pkg/srv/Name or pkg/action/Name"
        )
    for name in candidates:
        # the type store reads a package's file too, and says where a malformed one is wrong
        if _in_store(name) or interface_file(name, index) is not None:
            return name
    raise CliUsageError(
        f"unknown interface type '{text}'",
        expected="a type such as geometry_msgs/msg/Twist (`launchkit interface list`)",
    )


def _in_store(name: str) -> bool:
    package, kind, short = name.split("/")
    try:
        fields_of(f"{package}/{kind}/{short}{_PARTS[kind][0]}")
    except (LookupError, MessageTypeError):
        return False
    return True


def _show(args: argparse.Namespace) -> int:
    text = args.type
    if text == "-":
        text = sys.stdin.readline().strip()
    index = PackageIndex()
    name = _resolve(text, index)
    for line in show_lines(name, index, not args.no_comments, args.all_comments):
        print(line)
    return 0


def show_lines(
    name: str, index: PackageIndex, comments: bool, nested_comments: bool, indent: str = ""
) -> list[str]:
    """What ``ros2 interface show`` prints for ``pkg/kind/Name``: its file's lines with each
    nested message type expanded under its field, one tab deeper."""
    path = interface_file(name, index)
    if path is None:
        return _rebuilt(name, indent)
    out: list[str] = []
    package = name.split("/", 1)[0]
    for line in file_lines(path, package):
        shown = line.shown(comments)
        if shown is not None:
            out.append(indent + shown if shown else "")
        if line.nested_type is not None:
            out += show_lines(
                line.nested_type, index, nested_comments, nested_comments, indent + "\t"
            )
    return out


def _rebuilt(name: str, indent: str) -> list[str]:
    """The text of a type only the type store knows, rebuilt from its fields."""
    package, kind, short = name.split("/")
    lines: list[str] = []
    for number, part in enumerate(_PARTS[kind]):
        if number:
            lines.append(indent + SEPARATOR)
        lines += definition(f"{package}/{kind}/{short}{part}", indent)
    return lines


def definition(type_name: str, indent: str = "") -> list[str]:
    """A stored message type's fields and constants as ``.msg`` lines, nested types indented."""
    package = type_name.split("/", 1)[0]
    lines = [f"{indent}{base} {name}={value}" for name, base, value in constants_of(type_name)]
    for name, desc in fields_of(type_name):
        if name == _PLACEHOLDER:
            continue
        lines.append(f"{indent}{_type_text(desc, package)} {name}")
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


def _type_text(desc: Any, package: str) -> str:
    """A field's type as a ``.msg`` file writes it (another package's type as ``pkg/Name``)."""
    kind, detail = desc
    if kind == _BASE:
        base, bound = detail
        return f"{base}<={bound}" if bound else str(base)
    if kind == _NAME:
        owner, _, name = str(detail).split("/")
        return name if owner == package else f"{owner}/{name}"
    inner = _type_text(detail[0], package)
    if kind == _ARRAY:
        return f"{inner}[{detail[1]}]"
    return f"{inner}[<={detail[1]}]" if detail[1] else f"{inner}[]"


def _proto(args: argparse.Namespace) -> int:
    from launchkit.ros.message_text import to_yaml

    name = _resolve(args.type, PackageIndex())
    package, kind, short = name.split("/")
    try:
        message = get_message(f"{package}/{kind}/{short}{_PARTS[kind][0]}")()
    except MessageTypeError:
        raise CliUsageError(
            f"{name} has an interface file but no type launchkit can build",
            expected="a type of `launchkit interface list`",
        ) from None
    text = to_yaml(message)
    print(text if args.no_quotes else f'"{text}"')
    return 0
