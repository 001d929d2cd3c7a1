"""``launch_ros.parameter_descriptions`` (``ParameterValue``, ``ParameterFile``,
``Parameter``) and turning a ``Node(parameters=[...])`` list into launchkit's parameter entries.

Typing follows launch_ros: a plain ``str`` stays a string, numbers and booleans keep their
type, a substitution's text is read as YAML (``'true'`` is a bool, ``'5'`` an int), a list of
strings and substitutions is one string, a list of lists is a list of strings, and
``ParameterValue(value, value_type=...)`` forces a type.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, get_args

import yaml

from launchkit.description import actions as lk
from launchkit.description.actions.parameters import ParamEntry, ParamRule
from launchkit.description.substitutions.base import Text
from launchkit.errors import LaunchFileError
from launchkit.frontend.python.values import SubstitutionLike, here, to_value

_SEP = "\x1f"  # ASCII unit separator
_SCALARS: dict[type, str] = {str: "str", int: "int", float: "float", bool: "bool"}


def type_name(value_type: Any) -> str | None:
    """launchkit's parameter type for a launch_ros ``value_type`` (``int``, ``List[str]``...)."""
    if value_type is None:
        return None
    if value_type in _SCALARS:
        return _SCALARS[value_type]
    args = get_args(value_type)
    if len(args) == 1 and args[0] in _SCALARS:
        return "list_of_" + _SCALARS[args[0]]
    raise LaunchFileError(
        f"unsupported parameter value_type {value_type!r}",
        here(),
        expected="str, int, float, bool, List[str], List[int], List[float] or List[bool]",
    )


class ParameterValue:
    """``launch_ros.parameter_descriptions.ParameterValue(value, value_type=None)``."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.value = value
        self.value_type = value_type
        self.kind = type_name(value_type)


class ParameterFile:
    """``launch_ros.parameter_descriptions.ParameterFile(param_file, allow_substs=False)``."""

    def __init__(self, param_file: Any, *, allow_substs: Any = False) -> None:
        self.param_file = param_file
        self.allow_substs = bool(allow_substs)


class Parameter:
    """``launch_ros.parameter_descriptions.Parameter(name, value, value_type=None)``: one
    parameter given on its own."""

    def __init__(self, name: Any, value: Any, *, value_type: Any = None) -> None:
        self.name = name
        self.value = ParameterValue(value, value_type=value_type)


def _yaml_text(value: Any) -> str:
    text = yaml.safe_dump(value, default_flow_style=True)
    return text.strip().removesuffix("...").strip()


def _is_substitution(item: Any) -> bool:
    return isinstance(item, SubstitutionLike)


def _entry(name: Any, value: Any) -> ParamEntry:
    where = here()
    if isinstance(value, ParameterValue):
        return lk.ParamValue(to_value(name), to_value(value.value), value.kind, None, where)
    if isinstance(value, bool | int | float):
        return lk.ParamValue(to_value(name), to_value(_yaml_text(value)), None, None, where)
    if isinstance(value, str):
        return lk.ParamValue(to_value(name), to_value(value), "str", None, where)
    if isinstance(value, list | tuple):
        items = list(value)
        if any(_is_substitution(i) for i in items) and all(
            isinstance(i, str) or _is_substitution(i) for i in items
        ):
            return lk.ParamValue(to_value(name), to_value(items), None, None, where)  # one text
        if items and all(isinstance(i, list | tuple) for i in items):
            # a list of strings: the items joined with a separator no text holds, split again
            joined = [
                part for i, item in enumerate(items) for part in ([_SEP] if i else []) + [item]
            ]
            return lk.ParamValue(
                to_value(name), to_value(joined), "list_of_str", (Text(_SEP),), where
            )
        if all(isinstance(i, bool | int | float | str) for i in items):
            uniform = items if len({type(i) for i in items}) <= 1 else [str(i) for i in items]
            if {type(i) for i in items} <= {int, float} and float in {type(i) for i in items}:
                uniform = [float(i) for i in items]
            return lk.ParamValue(to_value(name), to_value(_yaml_text(uniform)), None, None, where)
    if _is_substitution(value) or isinstance(value, Path):
        return lk.ParamValue(to_value(name), to_value(value), None, None, where)
    raise LaunchFileError(
        f"parameter {name!r} has a value of type {type(value).__name__}",
        where,
        expected="a str, int, float, bool, substitution, list of those, dict or ParameterValue",
    )


def _dict_entries(values: Mapping[Any, Any]) -> list[ParamEntry]:
    entries: list[ParamEntry] = []
    for name, value in values.items():
        if isinstance(value, Mapping):
            entries.append(lk.ParamGroup(to_value(name), _dict_entries(value)))  # type: ignore[arg-type]
        else:
            entries.append(_entry(name, value))
    return entries


def parameter_entries(parameters: Iterable[Any]) -> list[list[ParamEntry] | ParamEntry]:
    """``Node(parameters=[...])``: one item per element, in order (a dict is a list of its
    parameters, which launch_ros writes to one file; a path or ParameterFile is a file; a
    Parameter is one value)."""
    if isinstance(parameters, str | Mapping) or not isinstance(parameters, Iterable):
        raise LaunchFileError(
            f"parameters is a {type(parameters).__name__}",
            here(),
            expected="a list of dicts, parameter files and Parameter(...)",
        )
    out: list[list[ParamEntry] | ParamEntry] = []
    for item in parameters:
        if isinstance(item, Mapping):
            out.append(_dict_entries(item))
        elif isinstance(item, ParameterFile):
            out.append(lk.ParamFile(to_value(item.param_file), item.allow_substs, here()))
        elif isinstance(item, Parameter):
            entry = _entry(item.name, item.value)
            assert isinstance(entry, lk.ParamValue)
            out.append(ParamRule(entry))
        else:
            out.append(lk.ParamFile(to_value(item), False, here()))
    return out
