"""``<param>`` inside ``<node>`` (and ``parameters=[...]`` of a Python ``Node``): values, nested
groups and YAML files, their typing, and their order as launch_ros passes them."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import yaml

from launchkit.description.substitutions.base import Value, perform
from launchkit.description.substitutions.grammar import parse_value
from launchkit.errors import Location, RuntimeLaunchError
from launchkit.packages import is_file
from launchkit.safe_yaml import compose, read_text

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext

PARAM_TYPES = (
    "str",
    "bool",
    "int",
    "float",
    "list_of_str",
    "list_of_bool",
    "list_of_int",
    "list_of_float",
    "yaml",
)


@dataclass
class ParamValue:
    """``<param name="n" value="v" [type] [value-sep]/>``."""

    name: Value
    value: Value
    type: str | None = None
    sep: Value | None = None
    location: Location | None = None


@dataclass
class ParamGroup:
    """``<param name="n">`` with nested ``<param>`` children (names joined with dots)."""

    name: Value
    children: list[ParamValue | ParamGroup] = field(default_factory=list)


@dataclass
class ParamFile:
    """``<param from="file.yaml" [allow_substs]/>``."""

    path: Value
    allow_substs: bool = False
    location: Location | None = None


@dataclass
class ParamDict:
    """A ``parameters=[{...}]`` dict of a Python ``Node``: its values share one params file
    (a lone ``<param>`` of XML is one file of its own too)."""

    entries: list[ParamValue | ParamGroup] = field(default_factory=list)


@dataclass
class ParamRule:
    """``launch_ros.descriptions.Parameter(name, value)``: one ``-p name:=value`` item."""

    param: ParamValue


ParamEntry = ParamValue | ParamGroup | ParamFile | ParamDict | ParamRule

#: One item of a node's evaluated parameters: values for one generated params file (dotted
#: names; a ParamRule's one value), or a params file passed as it is.
NodeParams = dict[str, Any] | Path


def typed_value(text: str, kind: str | None, location: Location | None) -> Any:
    """``text`` converted as ROS does: YAML inference unless ``type`` says otherwise."""
    try:
        if kind == "str":
            return text
        if kind is None or kind == "yaml":
            value = yaml.safe_load(text) if text.strip() else text
            return text if value is None else value
        if kind == "bool":
            value = yaml.safe_load(text)
            if isinstance(value, bool):
                return value
            raise ValueError
        if kind == "int":
            return int(text)
        if kind == "float":
            return float(text)
    except (ValueError, yaml.YAMLError):
        shown = text if len(text) <= 60 else text[:57] + "..."
        if kind is None or kind == "yaml":  # launch_ros refuses it too
            raise RuntimeLaunchError(
                f"parameter value {shown!r} is not valid YAML",
                location,
                expected='a YAML value, or type="str" to pass it as text',
            ) from None
        raise RuntimeLaunchError(
            f"parameter value {shown!r} is not a {kind}", location, expected=f"a {kind} value"
        ) from None
    raise RuntimeLaunchError(
        f"unknown parameter type {kind!r}", location, expected="one of " + ", ".join(PARAM_TYPES)
    )


def evaluate_value(param: ParamValue, context: LaunchContext) -> Any:
    """The typed value of one ``<param>``."""
    text = perform(param.value, context)
    if param.sep is not None or (param.type or "").startswith("list_of_"):
        item_type = (param.type or "").removeprefix("list_of_") or None
        if param.sep is not None:
            items = text.split(perform(param.sep, context))
            return [typed_value(i, item_type, param.location) for i in items]
        value = yaml.safe_load(text)
        if not isinstance(value, list):
            raise RuntimeLaunchError(
                f"parameter value {text!r} is not a list",
                param.location,
                expected="a YAML list such as [1, 2] or a value-sep attribute",
            )
        return [typed_value(str(i), item_type, param.location) for i in value]
    return typed_value(text, param.type, param.location)


def evaluate_params(entries: list[ParamEntry], context: LaunchContext) -> list[NodeParams]:
    """A node's parameters in launch_ros's order: every top-level ``<param name>`` (XML) or
    dict (Python) is a set of values of its own (one params file each), every ``from`` file is
    passed as it is. Later ones win, as on the command line."""
    evaluated: list[NodeParams] = []

    def visit(items: list[ParamValue | ParamGroup], prefix: str, values: dict[str, Any]) -> None:
        for item in items:
            name = prefix + perform(item.name, context)
            if isinstance(item, ParamGroup):
                visit(item.children, name + ".", values)
            else:
                values[name] = evaluate_value(item, context)

    for entry in entries:
        if isinstance(entry, ParamFile):
            evaluated.append(params_file(entry, context))
            continue
        values: dict[str, Any] = {}
        if isinstance(entry, ParamDict):
            visit(entry.entries, "", values)
        else:
            visit([entry.param if isinstance(entry, ParamRule) else entry], "", values)
        evaluated.append(values)
    return evaluated


def params_file(entry: ParamFile, context: LaunchContext) -> Path:
    """The file a ``<param from=...>`` names (a copy with its substitutions performed when
    ``allow_substs``); an error when it does not exist."""
    path = Path(perform(entry.path, context))
    if not is_file(path):
        raise RuntimeLaunchError(
            f"parameter file '{path}' does not exist", entry.location, expected="a YAML file"
        )
    text = read_text(path, entry.location)  # a located error for bytes that are not UTF-8
    if not entry.allow_substs:
        compose(text, path)  # refused here, before anything starts, rather than by the node
        return path.resolve()
    text = perform(parse_value(text, Location(str(path))), context)
    scratch = context.write_scratch_file("params_", ".yaml", text)
    compose(text, path)  # errors name the user's file (lines as substituted)
    return scratch
