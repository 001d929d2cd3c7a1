"""Parameters: typed values, ``--params-file`` YAML in ROS's format and ``-p`` overrides."""

from __future__ import annotations

import array
import enum
import re
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import Location, UserError
from launchkit.ros.arguments import RosArguments
from launchkit.safe_yaml import load_file

PARAMETER_SEPARATOR_STRING = "."


class ParameterError(UserError):
    """A parameter file or value that cannot be used."""


class Type(enum.Enum):
    """A parameter's type (``Parameter.Type``), valued as rcl_interfaces/msg/ParameterType."""

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
    def from_parameter_value(cls, parameter_value: Any) -> Type:
        """The type of a Python value, as rclpy infers it (TypeError if none fits)."""
        if parameter_value is None:
            return cls.NOT_SET
        if isinstance(parameter_value, bool):
            return cls.BOOL
        if isinstance(parameter_value, int):
            return cls.INTEGER
        if isinstance(parameter_value, float):
            return cls.DOUBLE
        if isinstance(parameter_value, str):
            return cls.STRING
        if isinstance(parameter_value, (list, tuple, array.array)):
            items = list(parameter_value)
            for kind, item_type in _ARRAY_TYPES:
                if all(isinstance(v, kind) for v in items):
                    return item_type
            raise TypeError(
                f"The given value is not a list of one of the allowed types '{parameter_value}'."
            )
        raise TypeError(f"The given value is not one of the allowed types '{parameter_value}'.")

    def check(self, parameter_value: Any) -> bool:
        """Whether ``parameter_value`` is a value of this type."""
        sequence: tuple[type, ...] = (list, tuple)
        if self in (Type.INTEGER_ARRAY, Type.DOUBLE_ARRAY):
            sequence = (list, tuple, array.array)
        if self == Type.NOT_SET:
            return parameter_value is None
        scalar = _SCALARS.get(self)
        if scalar is not None:
            return isinstance(parameter_value, scalar)
        if not isinstance(parameter_value, sequence):
            return False
        items: list[Any] = list(parameter_value)  # type: ignore[call-overload]
        if self == Type.BYTE_ARRAY:
            return all(isinstance(v, bytes) and len(v) == 1 for v in items)
        return all(isinstance(v, _ITEMS[self]) for v in items)


_ARRAY_TYPES: tuple[tuple[type, Type], ...] = (
    (bytes, Type.BYTE_ARRAY),
    (bool, Type.BOOL_ARRAY),
    (int, Type.INTEGER_ARRAY),
    (float, Type.DOUBLE_ARRAY),
    (str, Type.STRING_ARRAY),
)
_SCALARS: dict[Type, type] = {Type.BOOL: bool, Type.INTEGER: int, Type.DOUBLE: float}
_SCALARS[Type.STRING] = str
_ITEMS: dict[Type, type] = {
    Type.BOOL_ARRAY: bool,
    Type.INTEGER_ARRAY: int,
    Type.DOUBLE_ARRAY: float,
    Type.STRING_ARRAY: str,
}

ParameterType = Type  # launchkit's earlier name


class Parameter:
    """A named, typed parameter value (``.name``, ``.value``, ``.type_``): rclpy's ``Parameter``.

    ``Parameter(name, value=v)`` infers the type; a type and a value that disagree are a
    ValueError (no conversion, as rclpy: an integer is not a double).
    """

    Type = ParameterType

    def __init__(self, name: str, type_: ParameterType | None = None, value: Any = None) -> None:
        if type_ is None:
            type_ = ParameterType.from_parameter_value(value)
        if not isinstance(type_, ParameterType):
            raise TypeError(f"type must be an instance of '{ParameterType!r}'")
        if not type_.check(value):
            raise ValueError(f"Type '{type_}' and value '{value}' do not agree")
        self._name = name
        self._type_ = type_
        self._value = value

    @property
    def name(self) -> str:
        """The parameter's name."""
        return self._name

    @property
    def type_(self) -> ParameterType:
        """The parameter's type."""
        return self._type_

    @property
    def value(self) -> Any:
        """The parameter's value (None when NOT_SET)."""
        return self._value

    def __repr__(self) -> str:
        return f"Parameter({self.name!r}, {self.type_.name}, {self.value!r})"

    def get_parameter_value(self) -> Any:
        """This value as an rcl_interfaces/msg/ParameterValue."""
        from launchkit.ros.msgs import get_message

        msg = get_message("rcl_interfaces/msg/ParameterValue")(type=self.type_.value)
        field = _VALUE_FIELDS.get(self.type_)
        if field is not None:
            value = self.value
            if isinstance(value, tuple):
                value = list(value)
            setattr(msg, field, value)
        return msg

    to_msg_value = get_parameter_value

    def to_parameter_msg(self) -> Any:
        """This parameter as an rcl_interfaces/msg/Parameter."""
        from launchkit.ros.msgs import get_message

        return get_message("rcl_interfaces/msg/Parameter")(
            name=self.name, value=self.get_parameter_value()
        )

    @classmethod
    def from_parameter_msg(cls, param_msg: Any) -> Parameter:
        """From an rcl_interfaces/msg/Parameter."""
        return cls.from_msg_value(param_msg.name, param_msg.value)

    @classmethod
    def from_msg_value(cls, name: str, msg: Any) -> Parameter:
        """From a name and an rcl_interfaces/msg/ParameterValue."""
        type_ = ParameterType(msg.type)
        return cls(name, type_, _python_value(type_, msg))


def parameter_value_to_python(parameter_value: Any) -> Any:
    """The Python value of an rcl_interfaces/msg/ParameterValue (None when NOT_SET)."""
    try:
        type_ = Type(parameter_value.type)
    except ValueError:
        raise RuntimeError(f"unexpected parameter type {parameter_value.type}") from None
    value = _python_value(type_, parameter_value)
    return list(value) if isinstance(value, (tuple, array.array)) else value


def _python_value(type_: Type, msg: Any) -> Any:
    field = _VALUE_FIELDS.get(type_)
    if field is None:
        return None
    value = getattr(msg, field)
    if type_ == Type.BYTE_ARRAY:
        return [bytes([b]) if isinstance(b, int) else bytes(b) for b in value]
    if not isinstance(value, array.array) and hasattr(value, "tolist"):  # a numpy array
        value = value.tolist()
    if type_ == Type.DOUBLE_ARRAY and isinstance(value, list):
        return [float(v) for v in value]
    return list(value) if isinstance(value, tuple) else value


def parameter_from_value(name: str, value: Any) -> Parameter:
    """A parameter for a value from a launch file, a params file or the command line: rcl's
    leniency (a list of integers and floats is a double array, bytes a byte array)."""
    if isinstance(value, (bytes, bytearray)):
        value = [bytes([b]) for b in value]
    elif isinstance(value, (list, tuple)) and value:
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
        if numbers and any(isinstance(v, float) for v in value):
            value = [float(v) for v in value]
    try:
        return Parameter(name, value=value)
    except TypeError as exc:
        raise ParameterError(
            f"unsupported value {value!r} for parameter '{name}'",
            expected="bool, int, float, str or a list of one of them",
        ) from exc


_VALUE_FIELDS = {
    Type.BOOL: "bool_value",
    Type.INTEGER: "integer_value",
    Type.DOUBLE: "double_value",
    Type.STRING: "string_value",
    Type.BYTE_ARRAY: "byte_array_value",
    Type.BOOL_ARRAY: "bool_array_value",
    Type.INTEGER_ARRAY: "integer_array_value",
    Type.DOUBLE_ARRAY: "double_array_value",
    Type.STRING_ARRAY: "string_array_value",
}


def get_parameter_value(string_value: str) -> Any:
    """An rcl_interfaces/msg/ParameterValue guessed from text, as ``ros2 param set`` reads it
    (YAML; a list of mixed types, or anything else, is a string)."""
    from launchkit.ros.msgs import get_message

    value = get_message("rcl_interfaces/msg/ParameterValue")()
    try:
        parsed = yaml.safe_load(string_value)
    except yaml.YAMLError:
        parsed = string_value
    type_ = Type.STRING
    if isinstance(parsed, (bool, int, float)):
        type_ = Type.from_parameter_value(parsed)
    elif isinstance(parsed, list):
        kinds = ((bool, Type.BOOL_ARRAY), (int, Type.INTEGER_ARRAY), (float, Type.DOUBLE_ARRAY))
        for kind, array_type in (*kinds, (str, Type.STRING_ARRAY)):
            if all(isinstance(v, kind) for v in parsed):
                type_ = array_type
                break
    value.type = type_.value
    if type_ == Type.STRING:
        value.string_value = parsed if isinstance(parsed, str) else string_value
    else:
        setattr(value, _VALUE_FIELDS[type_], parsed)
    return value


def parameter_dict_from_yaml_file(
    parameter_file: str,
    use_wildcard: bool = False,
    target_nodes: list[str] | None = None,
    namespace: str = "",
) -> dict[str, Any]:
    """rcl_interfaces/msg/Parameter messages by name from a ROS params file (rclpy's): the
    entries of ``target_nodes`` (all when none), after ``/**`` with ``use_wildcard``."""
    from launchkit.ros.msgs import get_message

    with open(parameter_file) as stream:
        document = yaml.safe_load(stream)
    keys: list[str] = []
    if use_wildcard and "/**" in document:
        keys.append("/**")
    if target_nodes:
        for node in target_nodes:
            if node not in document:
                raise RuntimeError(
                    f"Param file does not contain parameters for {node},"
                    f"only for nodes: {list(document.keys())} "
                )
            keys.append(node)
    else:
        keys.extend(k for k in document if k != "/**")
    if not keys:
        raise RuntimeError("Param file does not contain selected parameters")
    values: dict[str, Any] = {}
    for key in keys:
        entry = document[key]
        if not isinstance(entry, dict) or "ros__parameters" not in entry:
            raise RuntimeError(f"YAML file is not a valid ROS parameter file for node {key}")
        values.update(entry["ros__parameters"])
    message = get_message("rcl_interfaces/msg/Parameter")
    return {
        name: message(name=name, value=get_parameter_value(str(value)))
        for name, value in flatten(values, namespace).items()
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
