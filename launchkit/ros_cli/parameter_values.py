"""A remote node's parameters for the ``param`` verbs: its parameter services called, and
``rcl_interfaces/msg/ParameterValue`` made from text and turned into Python values the way
rclpy does (``get_parameter_value``, ``parameter_value_to_python``)."""

from __future__ import annotations

import array
from typing import Any

import yaml

from launchkit.errors import RuntimeLaunchError
from launchkit.ros.message_data import fields_of
from launchkit.ros.message_text import rosidl_value
from launchkit.ros.msgs import get_message, get_service

_VALUE = "rcl_interfaces/msg/ParameterValue"
#: ParameterType number -> the ParameterValue field that holds such a value
_FIELDS = {
    1: "bool_value",
    2: "integer_value",
    3: "double_value",
    4: "string_value",
    5: "byte_array_value",
    6: "bool_array_value",
    7: "integer_array_value",
    8: "double_array_value",
    9: "string_array_value",
}
#: ParameterType number -> the name ros2 param prints for it
TYPE_NAMES = {
    0: "not set",
    1: "boolean",
    2: "integer",
    3: "double",
    4: "string",
    5: "byte array",
    6: "boolean array",
    7: "integer array",
    8: "double array",
    9: "string array",
}
_SERVICE_WAIT = 5.0  # seconds, as ros2param waits for a node's parameter services
_CALL_TIMEOUT = 10.0


def value_from_text(text: str | None) -> Any:
    """The ParameterValue ``text`` means, typed as rclpy's ``get_parameter_value`` types it
    (YAML: ``true``, ``5``, ``5.0``, ``[1, 2]``; anything else a string); None: not set."""
    value_class = get_message(_VALUE)
    if text is None:
        return value_class(type=0)
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        data = text
    if isinstance(data, bool):
        return value_class(type=1, bool_value=data)
    if isinstance(data, int):
        return value_class(type=2, integer_value=data)
    if isinstance(data, float):
        return value_class(type=3, double_value=data)
    if isinstance(data, list):
        for kind, number, field in (
            (bool, 6, "bool_array_value"),
            (int, 7, "integer_array_value"),
            (float, 8, "double_array_value"),
            (str, 9, "string_array_value"),
        ):
            if all(isinstance(v, kind) and (kind is bool or not isinstance(v, bool)) for v in data):
                return value_class(type=number, **{field: data})
    return value_class(type=4, string_value=data if isinstance(data, str) else text)


def python_value(value: Any) -> Any:
    """A ParameterValue as rclpy's ``parameter_value_to_python`` gives it (None when not set;
    a list for an array, of ``bytes`` for a byte array)."""
    field = _FIELDS.get(value.type)
    if field is None:
        return None
    held = rosidl_value(getattr(value, field), dict(fields_of(_VALUE))[field])
    return list(held) if isinstance(held, (list, array.array)) else held


def _snake(name: str) -> str:
    """``ListParameters`` -> ``list_parameters`` (the service's name under the node)."""
    return "".join("_" + c.lower() if c.isupper() else c for c in name).lstrip("_")


class NoParameterServices(RuntimeLaunchError):
    """A node that does not answer on its parameter services (it has none, or is gone)."""


class ParameterClient:
    """The parameter services of node ``target``, called from the command's ``node``."""

    def __init__(self, node: Any, target: str) -> None:
        self.node = node
        self.target = target

    def _call(self, service: str, request: Any) -> Any:
        srv = get_service(f"rcl_interfaces/srv/{service}")
        name = f"{self.target}/{_snake(service)}"
        client = self.node.create_client(srv, name)
        if not client.wait_for_service(timeout_sec=_SERVICE_WAIT):
            raise NoParameterServices(
                f"Wait for service timed out waiting for parameter services for node {self.target}"
            )
        try:
            response = client.call(request, timeout_sec=_CALL_TIMEOUT)
        except Exception as exc:  # the library's ServiceCallError, or a broken answer
            raise RuntimeLaunchError(
                f"Exception while calling service of node '{self.target}': {exc}"
            ) from None
        if response is None:
            raise RuntimeLaunchError(f"{name}: no answer within {_CALL_TIMEOUT:g} s")
        return response

    def names(self, prefixes: list[str]) -> list[str]:
        """The names of the node's parameters (those under ``prefixes`` when given)."""
        srv = get_service("rcl_interfaces/srv/ListParameters")
        return list(self._call("ListParameters", srv.Request(prefixes=prefixes)).result.names)

    def get(self, names: list[str]) -> list[Any]:
        """The ParameterValue of each name (none at all for an undeclared name, as rclpy
        answers)."""
        srv = get_service("rcl_interfaces/srv/GetParameters")
        return list(self._call("GetParameters", srv.Request(names=names)).values)

    def set(self, values: dict[str, Any]) -> list[Any]:
        """Set each name to its ParameterValue; the SetParametersResult of each."""
        srv = get_service("rcl_interfaces/srv/SetParameters")
        parameter = get_message("rcl_interfaces/msg/Parameter")
        request = srv.Request(parameters=[parameter(name=n, value=v) for n, v in values.items()])
        return list(self._call("SetParameters", request).results)

    def describe(self, names: list[str]) -> list[Any]:
        """The ParameterDescriptor of each name."""
        srv = get_service("rcl_interfaces/srv/DescribeParameters")
        return list(self._call("DescribeParameters", srv.Request(names=names)).descriptors)

    def types(self, names: list[str]) -> dict[str, str]:
        """The type of each name, as ros2 param list --param-type prints it."""
        return {d.name: TYPE_NAMES.get(d.type, "not set") for d in self.describe(names)}
