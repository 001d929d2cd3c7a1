"""Parameters: typed values, ``--params-file`` YAML in ROS's format and ``-p`` overrides."""

from __future__ import annotations

import enum
import re
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import Location, UserError
from launchkit.ros.arguments import RosArguments
from launchkit.safe_yaml import load_file


class ParameterError(UserError):
    """A parameter file or value that cannot be used."""


class ParameterType(enum.IntEnum):
    """rcl_interfaces/msg/ParameterType values."""

    NOT_SET = 0
    BOOL = 1
    INTEGER = 2
    DOUBLE = 3
    STRING = 4
    BYTE_ARRAY = 5
    BOOL_ARRAY = 6
    INTEGER_ARRAY = 7
    DOUBLE_ARRAY = 8
    STRING_ARRAY = 9

    @classmethod
    def from_value(cls, value: Any) -> ParameterType:
        """The type rclpy infers for a Python value."""
        if value is None:
            return cls.NOT_SET
        if isinstance(value, bool):
            return cls.BOOL
        if isinstance(value, int):
            return cls.INTEGER
        if isinstance(value, float):
            return cls.DOUBLE
        if isinstance(value, str):
            return cls.STRING
        if isinstance(value, (bytes, bytearray)):
            return cls.BYTE_ARRAY
        if isinstance(value, (list, tuple)):
            items = list(value)
            if items and all(isinstance(v, bool) for v in items):
                return cls.BOOL_ARRAY
            if items and all(isinstance(v, int) and not isinstance(v, bool) for v in items):
                return cls.INTEGER_ARRAY
            if items and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in items
            ):
                return cls.DOUBLE_ARRAY
            if all(isinstance(v, str) for v in items):
                return cls.STRING_ARRAY
        raise ParameterError(
            f"unsupported parameter value {value!r}",
            expected="bool, int, float, str, bytes or a list of one of them",
        )


class Parameter:
    """A named, typed parameter value (``.name``, ``.value``, ``.type_``), like rclpy's."""

    Type = ParameterType

    def __init__(self, name: str, type_: ParameterType | None = None, value: Any = None) -> None:
        if type_ is None:
            type_ = ParameterType.from_value(value)
        if type_ == ParameterType.DOUBLE_ARRAY and value is not None:
            value = [float(v) for v in value]
        elif type_ == ParameterType.DOUBLE and isinstance(value, int):
            value = float(value)
        self.name = name
        self.type_ = type_
        self.value = value

    def __repr__(self) -> str:
        return f"Parameter({self.name!r}, {self.type_.name}, {self.value!r})"

    def to_msg_value(self) -> Any:
        """This value as an rcl_interfaces/msg/ParameterValue."""
        from launchkit.ros.msgs import get_message

        value_cls = get_message("rcl_interfaces/msg/ParameterValue")
        msg = value_cls(type=int(self.type_))
        field = _VALUE_FIELDS.get(self.type_)
        if field is not None:
            setattr(msg, field, list(self.value) if isinstance(self.value, tuple) else self.value)
        return msg

    @classmethod
    def from_msg_value(cls, name: str, msg: Any) -> Parameter:
        """Build from an rcl_interfaces/msg/ParameterValue."""
        type_ = ParameterType(msg.type)
        field = _VALUE_FIELDS.get(type_)
        value = None if field is None else getattr(msg, field)
        if value is not None and hasattr(value, "tolist"):
            value = value.tolist()
        if type_ == ParameterType.BYTE_ARRAY and value is not None:
            value = bytes(value)
        return cls(name, type_, value)


_VALUE_FIELDS = {
    ParameterType.BOOL: "bool_value",
    ParameterType.INTEGER: "integer_value",
    ParameterType.DOUBLE: "double_value",
    ParameterType.STRING: "string_value",
    ParameterType.BYTE_ARRAY: "byte_array_value",
    ParameterType.BOOL_ARRAY: "bool_array_value",
    ParameterType.INTEGER_ARRAY: "integer_array_value",
    ParameterType.DOUBLE_ARRAY: "double_array_value",
    ParameterType.STRING_ARRAY: "string_array_value",
}


def parse_value_text(text: str) -> Any:
    """A ``-p name:=value`` value, read as YAML the way rcl reads it."""
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    if value is None and text.strip() == "":
        return ""
    if isinstance(value, (dict, type(None))):
        return text
    return value


def overrides_for(args: RosArguments, node_name: str, node_fqn: str) -> dict[str, Any]:
    """The parameter values for the node ``node_fqn`` from files and ``-p`` items, in order."""
    values: dict[str, Any] = {}
    for kind, index in args.param_order:
        if kind == "f":
            values.update(load_params_file(args.params_files[index], node_fqn))
        else:
            target, name, text = args.params[index]
            if target is None or target in (node_name, node_fqn, node_fqn.lstrip("/")):
                values[name] = parse_value_text(text)
    return values


def load_params_file(path: Path, node_fqn: str) -> dict[str, Any]:
    """The parameters a ROS params YAML file gives ``node_fqn`` (``/**``, names, wildcards)."""
    document = load_file(path)  # located errors; bounded depth, aliases and numbers
    if document is None:
        return {}
    if not isinstance(document, dict):
        raise ParameterError(
            f"parameter file {str(path)!r} has no node entries",
            Location(str(path)),
            expected="'/**:' or '<node name>:' keys with 'ros__parameters:'",
        )
    values: dict[str, Any] = {}
    for key, section in document.items():
        if not _node_pattern_matches(str(key), node_fqn):
            continue
        if not isinstance(section, dict) or "ros__parameters" not in section:
            raise ParameterError(
                f"parameter file {str(path)!r}: entry {key!r} has no 'ros__parameters'",
                Location(str(path)),
                expected=f"{key}: {{ros__parameters: {{name: value}}}}",
            )
        params = section["ros__parameters"] or {}
        if not isinstance(params, dict):
            raise ParameterError(
                f"parameter file {str(path)!r}: 'ros__parameters' of {key!r} is not a mapping",
                Location(str(path)),
            )
        values.update(flatten(params))
    return values


def flatten(params: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested mappings to dotted names: ``{a: {b: 1}}`` -> ``{"a.b": 1}``."""
    out: dict[str, Any] = {}
    for key, value in params.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(flatten(value, name + "."))
        else:
            out[name] = value
    return out


def _node_pattern_matches(pattern: str, node_fqn: str) -> bool:
    # token-wise, as rcl: "**" is any number of tokens, "*" any characters within one token
    regex = ""
    for token in pattern.strip("/").split("/"):
        if token == "**":
            regex += "(?:/[^/]+)*"
        else:
            regex += "/" + "[^/]*".join(re.escape(piece) for piece in token.split("*"))
    return re.fullmatch(regex, node_fqn) is not None
