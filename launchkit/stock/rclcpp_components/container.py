"""``component_container``: one process, one executor, many launchkit Python nodes loaded
on request through ``~/_container/load_node`` (composition_interfaces), as rclcpp's does."""

from __future__ import annotations

import sys
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.composition_interfaces.srv import ListNodes, LoadNode, UnloadNode
from launchkit.ros.params import Parameter
from launchkit.stock import _entry
from launchkit.stock.rclcpp_components.plugins import find_component


class ComponentManager:
    """The container node's services and the components it holds."""

    def __init__(self, node: ros.Node, executor: ros.Executor) -> None:
        self.node = node
        self.executor = executor
        self.components: dict[int, Any] = {}
        self._next_id = 1
        node.create_service(LoadNode, "~/_container/load_node", self.load)
        node.create_service(UnloadNode, "~/_container/unload_node", self.unload)
        node.create_service(ListNodes, "~/_container/list_nodes", self.list)

    def load(self, request: Any, response: Any) -> Any:
        """Create the component the request names and run it on the executor."""
        log = self.node.get_logger()
        try:
            component = find_component(request.package_name, request.plugin_name)
            instance = component(**self._options(request))
        except Exception as error:  # the request failed: say why in the response
            message = error.format() if hasattr(error, "format") else f"{error}"
            log.error(f"failed to load '{request.plugin_name}': {message}")
            response.success = False
            response.error_messsage = message
            return response
        unique_id = self._next_id
        self._next_id += 1
        self.components[unique_id] = instance
        self.executor.add_node(instance)
        response.success = True
        response.full_node_name = instance.get_fully_qualified_name()
        response.unique_id = unique_id
        log.info(f"Load Library: {request.plugin_name} as {response.full_node_name}")
        return response

    @staticmethod
    def _options(request: Any) -> dict[str, Any]:
        """What rclcpp puts in the component's NodeOptions, as Node keyword arguments."""
        arguments = ["--ros-args"]
        if request.node_name:
            arguments += ["-r", f"__node:={request.node_name}"]
        if request.node_namespace:
            arguments += ["-r", f"__ns:={request.node_namespace}"]
        for rule in request.remap_rules:
            arguments += ["-r", rule]
        overrides = [Parameter.from_msg_value(p.name, p.value) for p in request.parameters]
        return {
            "cli_args": arguments,
            "parameter_overrides": overrides,
            "use_global_arguments": False,
        }

    def unload(self, request: Any, response: Any) -> Any:
        """Stop and destroy a loaded component."""
        instance = self.components.pop(int(request.unique_id), None)
        if instance is None:
            response.success = False
            response.error_messsage = f"no node found with unique_id {request.unique_id}"
            return response
        self.executor.remove_node(instance)
        instance.destroy_node()
        response.success = True
        return response

    def list(self, _request: Any, response: Any) -> Any:
        """The loaded components' names and ids."""
        response.unique_ids = list(self.components)
        response.full_node_names = [c.get_fully_qualified_name() for c in self.components.values()]
        return response


def main(argv: list[str]) -> int:
    """Run the container until shutdown."""
    with _entry.ros_node(argv, "ComponentManager") as node:
        executor = ros.SingleThreadedExecutor()
        manager = ComponentManager(node, executor)
        executor.add_node(node)
        try:
            executor.spin()
        finally:
            for instance in manager.components.values():
                instance.destroy_node()
    return 0


if __name__ == "__main__":
    sys.exit(_entry.run(main, "component_container"))
