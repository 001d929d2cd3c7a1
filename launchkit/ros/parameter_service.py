"""The ``~/list_parameters``, ``~/get_parameters``, ``~/set_parameters``... services of a node,
answering as rclpy's ``ParameterService`` does."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from launchkit.ros.exceptions import (
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from launchkit.ros.msgs import get_message, get_service
from launchkit.ros.parameter_store import result_message
from launchkit.ros.params import Parameter
from launchkit.ros.qos import QoSProfile, qos_profile_parameters


class ParameterNode(Protocol):
    """What the services use of their node (:class:`launchkit.ros.Node`)."""

    def get_name(self) -> str:
        """The node's name."""

    def create_service(
        self,
        srv_type: Any,
        srv_name: str,
        callback: Callable[..., Any],
        *,
        qos_profile: QoSProfile | int = ...,
        callback_group: Any = ...,
        raw: bool = ...,
    ) -> Any:
        """Serve ``srv_name``."""

    def describe_parameter(self, name: str) -> Any:
        """A parameter's descriptor."""

    def get_parameter(self, name: str) -> Parameter:
        """A declared parameter."""

    def get_parameter_type(self, name: str) -> Any:
        """A parameter's type number."""

    def list_parameters(self, prefixes: list[str], depth: int) -> Any:
        """A ListParametersResult."""

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> Any:
        """Set all or none."""


_SERVICES = (
    ("DescribeParameters", "describe_parameters"),
    ("GetParameters", "get_parameters"),
    ("GetParameterTypes", "get_parameter_types"),
    ("ListParameters", "list_parameters"),
    ("SetParameters", "set_parameters"),
    ("SetParametersAtomically", "set_parameters_atomically"),
)


class ParameterService:
    """Serves a node's parameters (``<node name>/<service>``, rclpy's
    ``qos_profile_parameters``): what ``launchkit param`` and ``ros2 param`` call."""

    def __init__(self, node: ParameterNode) -> None:
        self.node = node
        for type_name, service in _SERVICES:
            node.create_service(
                get_service(f"rcl_interfaces/srv/{type_name}"),
                f"{node.get_name()}/{service}",
                getattr(self, f"_{service}"),
                qos_profile=qos_profile_parameters,
            )

    def _describe_parameters(self, request: Any, response: Any) -> Any:
        descriptors = []
        for name in request.names:
            try:
                descriptors.append(self.node.describe_parameter(name))
            except ParameterNotDeclaredException:
                descriptors = []  # one unknown name: none at all, as rclpy
                break
        response.descriptors = descriptors
        return response

    def _get_parameters(self, request: Any, response: Any) -> Any:
        values = []
        for name in request.names:
            try:
                values.append(self.node.get_parameter(name).get_parameter_value())
            except (ParameterNotDeclaredException, ParameterUninitializedException):
                values = []
                break
        response.values = values
        return response

    def _get_parameter_types(self, request: Any, response: Any) -> Any:
        types: list[int] = []
        for name in request.names:
            try:
                kind = self.node.get_parameter_type(name)
            except ParameterNotDeclaredException:
                types = []
                break
            types.append(getattr(kind, "value", kind))
        response.types = types
        return response

    def _list_parameters(self, request: Any, response: Any) -> Any:
        try:
            response.result = self.node.list_parameters(list(request.prefixes), int(request.depth))
        except (TypeError, ValueError):
            response.result = get_message("rcl_interfaces/msg/ListParametersResult")()
        return response

    def _set_parameters(self, request: Any, response: Any) -> Any:
        results = []
        for item in request.parameters:
            try:
                result = self.node.set_parameters_atomically([Parameter.from_parameter_msg(item)])
            except ParameterNotDeclaredException as exc:
                result = result_message(False, str(exc))
            results.append(result)
        response.results = results
        return response

    def _set_parameters_atomically(self, request: Any, response: Any) -> Any:
        try:
            response.result = self.node.set_parameters_atomically(
                [Parameter.from_parameter_msg(item) for item in request.parameters]
            )
        except ParameterNotDeclaredException as exc:
            response.result = result_message(False, str(exc))
        return response
