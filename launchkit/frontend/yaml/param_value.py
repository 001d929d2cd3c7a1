"""A YAML ``param`` value, typed as ROS types it (``launch_ros`` ``Node.parse_nested_parameters``
reading ``launch_yaml`` values; checked against the real Jazzy stack).

* ``value: 1.5``, ``value: true``, ``value: [1, 2]`` keep their YAML type;
* a string without substitutions stays a string (``value: '1.5'`` is the text ``1.5``), unlike
  XML, where every value is YAML-typed text;
* a string with substitutions is YAML-typed once they are performed (``value: $(var rate)``);
* a list holds scalars of one type; an item with substitutions is typed when performed;
* ``type: T`` checks a literal value against T (an integer is not a float, a string is not an
  integer) and converts a substituted one to T.

The result is a launchkit value and the type it is to be read as, so the description's
``ParamValue`` needs nothing YAML-specific: a typed scalar becomes its YAML text read by YAML's
rules, a list the text of a YAML flow list.
"""

from __future__ import annotations

from launchkit.description.substitutions.base import Substitution, Text, Value, literal
from launchkit.description.substitutions.grammar import parse_value
from launchkit.errors import LaunchFileError
from launchkit.frontend.yaml.scalars import describe, node_text, quoted
from launchkit.safe_yaml import Node

_SCALAR_TYPES: dict[str, type] = {"str": str, "bool": bool, "int": int, "float": float}
_LIST_TYPES: dict[str, type] = {f"list_of_{name}": kind for name, kind in _SCALAR_TYPES.items()}
_NAMES = {str: "text", bool: "boolean", int: "integer", float: "float"}


def _is(value: object, kind: type) -> bool:
    return type(value) is kind  # exact: a boolean is no integer, an integer no float


def param_value(node: Node, kind: str | None, what: str) -> tuple[Value, str | None]:
    """The value of ``node`` (``what`` names it in errors) and the type to read it as."""
    if node.kind == "map":
        raise _error(what, node, "a scalar or a list (nested parameters go in 'param: [...]')")
    if node.kind == "seq":
        return _list(node, kind, what)
    value = node.value
    if kind in _LIST_TYPES:
        raise _error(what, node, f"a list, as type is {kind}")
    if isinstance(value, str):
        parsed = parse_value(value, node.text_location)
        if literal(parsed) is None:
            return parsed, kind
        if kind in (None, "yaml", "str"):
            return parsed, "str"
        raise _error(what, node, f"a {kind} without quotes, as type is {kind}")
    if not isinstance(value, bool | int | float):
        raise _error(what, node, "text, a number or a boolean")
    if kind in _SCALAR_TYPES and not _is(value, _SCALAR_TYPES[kind]):
        raise _error(what, node, f"a {_NAMES[_SCALAR_TYPES[kind]]}, as type is {kind}")
    return (Text(node_text(node)),), kind


def _list(node: Node, kind: str | None, what: str) -> tuple[Value, str | None]:
    if kind in _SCALAR_TYPES:
        raise _error(what, node, f"a single value, as type is {kind}")
    wanted = _LIST_TYPES.get(kind or "")
    parts: list[Substitution] = [Text("[")]
    types: set[type] = set()
    for index, item in enumerate(node.items):
        if item.kind != "scalar" or item.value is None:
            raise _error(f"item {index + 1} of {what}", item, "text, a number or a boolean")
        if index:
            parts.append(Text(", "))
        value = item.value
        if isinstance(value, str):
            parsed = parse_value(value, item.text_location)
            text = literal(parsed)
            if text is None:
                # typed by YAML's rules once performed, as ROS types such an item
                parts.extend(parsed)
                continue
            parts.append(Text(quoted(text)))
        elif isinstance(value, bool | int | float):
            parts.append(Text(node_text(item)))
        else:
            raise _error(f"item {index + 1} of {what}", item, "text, a number or a boolean")
        types.add(type(value))
        if len(types) > 1 or (wanted is not None and type(value) is not wanted):
            expected = f"{_NAMES[wanted]}s, as type is {kind}" if wanted else "items of one type"
            raise _error(f"item {index + 1} of {what}", item, expected)
    parts.append(Text("]"))
    return tuple(parts), kind


def _error(what: str, node: Node, expected: str) -> LaunchFileError:
    return LaunchFileError(f"{what} is {describe(node)}", node.text_location, expected=expected)
