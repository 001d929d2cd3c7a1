"""The ``~/list_parameters``, ``~/get_parameters``, ``~/set_parameters``... services of a node."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, Protocol

from launchkit.ros.msgs import get_message, get_service
from launchkit.ros.node_params import SetParametersResult
from launchkit.ros.params import Parameter, ParameterType
from launchkit.ros.qos import qos_profile_parameters


class ParameterNode(Protocol):
    """What the services use of their node (:class:`launchkit.ros.Node`)."""

    def create_service(
        self, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any], **_: Any
    ) -> Any:
        """Serve ``srv_name``."""

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """The declared parameters under ``prefix`` (all of them for ``""``)."""

    def set_parameters(self, parameter_list: list[Parameter]) -> list[SetParametersResult]:
        """Set parameters one by one."""

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> SetParametersResult:
        """Set all or none."""


class ParameterService:
    """Serves a node's parameters the way rclpy does (for ``launchkit param ...``), with
    rclpy's ``qos_profile_parameters`` (depth 1000)."""

    def __init__(self, node: ParameterNode) -> None:
        self.node = node
        prefix = "~/"
        serve = functools.partial(node.create_service, qos_profile=qos_profile_parameters)
        serve(
            get_service("rcl_interfaces/srv/ListParameters"), prefix + "list_parameters", self._list
        )
        serve(get_service("rcl_interfaces/srv/GetParameters"), prefix + "get_parameters", self._get)
        serve(
            get_service("rcl_interfaces/srv/GetParameterTypes"),
            prefix + "get_parameter_types",
            self._types,
        )
        serve(get_service("rcl_interfaces/srv/SetParameters"), prefix + "set_parameters", self._set)
        serve(
            get_service("rcl_interfaces/srv/SetParametersAtomically"),
            prefix + "set_parameters_atomically",
            self._set_atomically,
        )
        serve(
            get_service("rcl_interfaces/srv/DescribeParameters"),
            prefix + "describe_parameters",
            self._describe,
        )

    def _list(self, request: Any, response: Any) -> Any:
        names = sorted(self.node.get_parameters_by_prefix(""))
        prefixes = list(request.prefixes)
        depth = int(request.depth)
        selected = []
        for name in names:
            if prefixes and not any(name == p or name.startswith(p + ".") for p in prefixes):
                continue
            if depth:
                rest = name
                for p in prefixes:
                    if name.startswith(p + "."):
                        rest = name[len(p) + 1 :]
                if rest.count(".") >= depth:
                    continue
            selected.append(name)
        found_prefixes = sorted({n.rpartition(".")[0] for n in selected if "." in n})
        result_cls = get_message("rcl_interfaces/msg/ListParametersResult")
        response.result = result_cls(names=selected, prefixes=found_prefixes)
        return response

    def _get(self, request: Any, response: Any) -> Any:
        declared = self.node.get_parameters_by_prefix("")
        values = []
        for name in request.names:
            param = declared.get(name, Parameter(name, ParameterType.NOT_SET, None))
            values.append(param.to_msg_value())
        response.values = values
        return response

    def _types(self, request: Any, response: Any) -> Any:
        declared = self.node.get_parameters_by_prefix("")
        response.types = [int(declared[n].type_) if n in declared else 0 for n in request.names]
        return response

    def _set(self, request: Any, response: Any) -> Any:
        params = [Parameter.from_msg_value(p.name, p.value) for p in request.parameters]
        results = self.node.set_parameters(params)
        result_cls = get_message("rcl_interfaces/msg/SetParametersResult")
        response.results = [result_cls(successful=r.successful, reason=r.reason) for r in results]
        return response

    def _set_atomically(self, request: Any, response: Any) -> Any:
        params = [Parameter.from_msg_value(p.name, p.value) for p in request.parameters]
        result = self.node.set_parameters_atomically(params)
        result_cls = get_message("rcl_interfaces/msg/SetParametersResult")
        response.result = result_cls(successful=result.successful, reason=result.reason)
        return response

    def _describe(self, request: Any, response: Any) -> Any:
        descriptor_cls = get_message("rcl_interfaces/msg/ParameterDescriptor")
        declared = self.node.get_parameters_by_prefix("")
        response.descriptors = [
            descriptor_cls(name=n, type=int(declared[n].type_) if n in declared else 0)
            for n in request.names
        ]
        return response
