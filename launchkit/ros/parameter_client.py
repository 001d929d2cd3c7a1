"""``AsyncParameterClient``: another node's parameters through its parameter services
(rclpy's ``rclpy.parameter_client``); every call returns a future of the service's response."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Protocol

from launchkit.ros.msgs import get_message, get_service
from launchkit.ros.params import Parameter, ParameterType, parameter_dict_from_yaml_file
from launchkit.ros.qos import QoSProfile, qos_profile_parameter_events, qos_profile_services_default
from launchkit.ros.task import Future

Done = Callable[[Future], Any] | None  # what is called with the future when it completes

_SERVICES = {
    "get": ("GetParameters", "get_parameters"),
    "list": ("ListParameters", "list_parameters"),
    "set": ("SetParameters", "set_parameters"),
    "types": ("GetParameterTypes", "get_parameter_types"),
    "describe": ("DescribeParameters", "describe_parameters"),
    "atomic": ("SetParametersAtomically", "set_parameters_atomically"),
}


class ClientNode(Protocol):
    """What the client uses of its node (:class:`launchkit.ros.Node`)."""

    def create_client(self, srv_type: Any, srv_name: str, **kwargs: Any) -> Any:
        """A service client."""

    def create_subscription(
        self, msg_type: Any, topic: str, callback: Callable[..., Any], qos: Any, **kwargs: Any
    ) -> Any:
        """A subscription."""


class AsyncParameterClient:
    """Lists, gets, sets and describes the parameters of ``remote_node_name``."""

    def __init__(
        self,
        node: ClientNode,
        remote_node_name: str,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: Any = None,
    ) -> None:
        self.remote_node_name = remote_node_name
        self.node = node
        self._clients = {
            key: node.create_client(
                get_service(f"rcl_interfaces/srv/{type_name}"),
                f"{remote_node_name}/{service}",
                qos_profile=qos_profile,
                callback_group=callback_group,
            )
            for key, (type_name, service) in _SERVICES.items()
        }

    def services_are_ready(self) -> bool:
        """Whether every parameter service of the remote node is up."""
        return all(client.service_is_ready() for client in self._clients.values())

    def wait_for_services(self, timeout_sec: float | None = None) -> bool:
        """Wait for the remote node's parameter services; False after ``timeout_sec``."""
        return all(c.wait_for_service(timeout_sec) for c in self._clients.values())

    def _call(self, key: str, callback: Done, **fields: Any) -> Future:
        client = self._clients[key]
        future: Future = client.call_async(client.srv_type.Request(**fields))
        if callback:
            future.add_done_callback(callback)
        return future

    def list_parameters(
        self, prefixes: list[str] | None = None, depth: int | None = None, callback: Done = None
    ) -> Future:
        """A future of the ListParameters response."""
        return self._call("list", callback, prefixes=prefixes or [], depth=depth or 0)

    def get_parameters(self, names: list[str], callback: Done = None) -> Future:
        """A future of the GetParameters response."""
        return self._call("get", callback, names=names)

    def describe_parameters(self, names: list[str], callback: Done = None) -> Future:
        """A future of the DescribeParameters response."""
        return self._call("describe", callback, names=names)

    def get_parameter_types(self, names: list[str], callback: Done = None) -> Future:
        """A future of the GetParameterTypes response."""
        return self._call("types", callback, names=names)

    def set_parameters(self, parameters: Sequence[Any], callback: Done = None) -> Future:
        """A future of the SetParameters response (Parameter objects or messages)."""
        return self._call("set", callback, parameters=_messages(parameters))

    def set_parameters_atomically(self, parameters: Sequence[Any], callback: Done = None) -> Future:
        """A future of the SetParametersAtomically response."""
        return self._call("atomic", callback, parameters=_messages(parameters))

    def delete_parameters(self, names: list[str], callback: Done = None) -> Future:
        """Unset (dynamically typed) parameters: a future of the SetParameters response."""
        unset = [Parameter(name, ParameterType.NOT_SET) for name in names]
        return self.set_parameters(unset, callback)

    def load_parameter_file(
        self, parameter_file: str, use_wildcard: bool = False, callback: Done = None
    ) -> Future:
        """Set the parameters of a params file: a future of the SetParameters response."""
        values = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters(list(values.values()), callback)

    def load_parameter_file_atomically(
        self, parameter_file: str, use_wildcard: bool = False, callback: Done = None
    ) -> Future:
        """Set the parameters of a params file all at once."""
        values = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters_atomically(list(values.values()), callback)

    def on_parameter_event(
        self,
        callback: Callable[..., Any],
        qos_profile: QoSProfile = qos_profile_parameter_events,
        **kwargs: Any,
    ) -> Any:
        """Subscribe ``callback`` to ``/parameter_events``."""
        event = get_message("rcl_interfaces/msg/ParameterEvent")
        return self.node.create_subscription(
            event, "/parameter_events", callback, qos_profile, **kwargs
        )


def _messages(parameters: Sequence[Any]) -> list[Any]:
    return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]
