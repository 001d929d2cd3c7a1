"""Composable nodes: ``ComposableNodeContainer`` / ``<node_container>`` (a container process
and the components to load into it) and ``LoadComposableNodes`` / ``<load_composable_node>``
(load into a running container), with ``ComposableNode`` / ``<composable_node>`` describing
one component.

Loading goes through the container's ``~/_container/load_node`` service
(composition_interfaces/srv/LoadNode) from the launcher's ROS node, one component after the
other, as launch_ros does; the request is built when the action runs (so the scope of the
action gives the namespace, global parameters and remaps).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from launchkit.description.actions.base import Action
from launchkit.description.actions.node import ExecuteNode, Remap
from launchkit.description.actions.parameters import (
    ParamEntry,
    ParamFile,
    evaluate_params,
    typed_value,
)
from launchkit.description.actions.ros_scope import NAMESPACE_CONFIGURATION, ros_namespace
from launchkit.description.ros_link import LoadRequest
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


@dataclass
class ComposableNode:
    """One component: its package and plugin, and the name, namespace, parameters, remaps
    and container-specific extra arguments it loads with."""

    package: Value
    plugin: Value
    name: Value | None = None
    namespace: Value | None = None
    params: list[ParamEntry] = field(default_factory=list)
    remaps: list[Remap] = field(default_factory=list)
    extra_arguments: list[ParamEntry] = field(default_factory=list)
    condition: Condition | None = None
    location: Location | None = None


def load_request(node: ComposableNode, context: LaunchContext) -> LoadRequest | None:
    """The LoadNode request for ``node`` in ``context`` (None when its condition is false)."""
    if node.condition is not None and not node.condition.evaluate(context):
        return None
    own = perform(node.namespace, context).strip() if node.namespace is not None else None
    namespace = ros_namespace(context.configurations.get(NAMESPACE_CONFIGURATION), own) or ""
    request = LoadRequest(
        package=perform(node.package, context),
        plugin=perform(node.plugin, context),
        node_name=perform(node.name, context) if node.name is not None else "",
        namespace=namespace,
    )
    request.remaps = [f"{src}:={dst}" for src, dst in context.scope.remaps]
    request.remaps += [f"{perform(r.src, context)}:={perform(r.dst, context)}" for r in node.remaps]
    for item in context.scope.global_params:
        if isinstance(item, str):
            request.parameters.append(Path(item))
        else:
            request.parameters.append((item[0], typed_value(item[1], None, node.location)))
    for given in evaluate_params(node.params, context):
        if isinstance(given, dict):
            request.parameters.extend(given.items())
        else:
            request.parameters.append(given)
    plain: list[ParamEntry] = [e for e in node.extra_arguments if not isinstance(e, ParamFile)]
    for extra in evaluate_params(plain, context):
        assert isinstance(extra, dict)
        request.extra_arguments.extend(extra.items())
    return request


def _describe(request: LoadRequest, container: str) -> str:
    name = f"{request.namespace.rstrip('/')}/{request.node_name}" if request.node_name else ""
    as_name = name or "its default name"
    return f"load {request.plugin} ({request.package}) as {as_name} into {container}"


class LoadComposableNodes(Action):
    """Load components into ``target``: a container action of this launch, or a container's
    node name."""

    TAG = "load_composable_node"

    def __init__(
        self,
        target: Value | ExecuteNode,
        nodes: Sequence[ComposableNode],
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.target = target
        self.nodes = list(nodes)

    def container_name(self, context: LaunchContext) -> str:
        """The target container's full node name."""
        if isinstance(self.target, ExecuteNode):
            name = getattr(self.target, "fqn", None) or self.target.full_name(context)
        else:
            name = perform(self.target, context)
        return name if name.startswith("/") else "/" + name

    def execute(self, context: LaunchContext) -> None:
        """Build the requests now and hand them to the launcher's ROS node."""
        container = self.container_name(context)
        requests = [r for r in (load_request(n, context) for n in self.nodes) if r is not None]
        if not requests:
            return
        link = context.ros()
        if link is None:
            for request in requests:
                context.log("INFO", _describe(request, container))
            return
        link.load_nodes(container, requests, context.runner.log)


class ComposableNodeContainer(ExecuteNode):
    """A container process (a ``<node>``) and the components loaded into it once it runs."""

    TAG = "node_container"

    def __init__(self, *args: Any, nodes: Sequence[ComposableNode] = (), **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.nodes = list(nodes)
        #: The container's full name once the action ran.
        self.fqn: str | None = None

    def execute(self, context: LaunchContext) -> None:
        """Start the container, then load its components."""
        self.fqn = self.full_name(context)
        super().execute(context)
        if self.nodes:
            LoadComposableNodes(self, self.nodes, self.location).visit(context)
