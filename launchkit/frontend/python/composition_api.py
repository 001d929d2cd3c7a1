"""Stand-ins for launch_ros's composition API: ``ComposableNodeContainer``,
``LoadComposableNodes`` and ``ComposableNode``."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from launchkit.description.actions import composition as lk
from launchkit.description.actions.node import ExecuteNode
from launchkit.description.conditions import Condition
from launchkit.errors import LaunchFileError
from launchkit.frontend.python.ros_api import flat_parameters, node_arguments, remap_rules
from launchkit.frontend.python.values import SubstitutionLike, here, optional_value, to_value


def ComposableNode(
    *,
    package: Any,
    plugin: Any,
    name: Any = None,
    namespace: Any = None,
    parameters: Iterable[Any] | None = None,
    remappings: Iterable[Any] | None = None,
    extra_arguments: Iterable[Any] | None = None,
    condition: Condition | None = None,
) -> lk.ComposableNode:
    """``launch_ros.descriptions.ComposableNode``."""
    return lk.ComposableNode(
        package=to_value(package),
        plugin=to_value(plugin),
        name=optional_value(name),
        namespace=optional_value(namespace),
        params=flat_parameters(parameters),
        remaps=remap_rules(remappings),
        extra_arguments=flat_parameters(extra_arguments),
        condition=condition,
        location=here(),
    )


def _descriptions(nodes: Iterable[Any] | None) -> list[lk.ComposableNode]:
    found = list(nodes or [])
    for node in found:
        if not isinstance(node, lk.ComposableNode):
            raise LaunchFileError(
                f"composable_node_descriptions holds a {type(node).__name__}",
                here(),
                expected="ComposableNode(package=..., plugin=..., name=...)",
            )
    return found


class ComposableNodeContainer(lk.ComposableNodeContainer):
    """``launch_ros.actions.ComposableNodeContainer(name=..., namespace=..., package=...,
    executable=..., composable_node_descriptions=[...])``."""

    def __init__(
        self,
        *,
        name: Any,
        namespace: Any,
        composable_node_descriptions: Iterable[Any] | None = None,
        **kwargs: Any,
    ) -> None:
        arguments = node_arguments(name=name, namespace=namespace, **kwargs)
        super().__init__(
            arguments.pop("pkg"),
            arguments.pop("exec"),
            arguments.pop("options"),
            nodes=_descriptions(composable_node_descriptions),
            **arguments,
        )


class LoadComposableNodes(lk.LoadComposableNodes):
    """``launch_ros.actions.LoadComposableNodes(composable_node_descriptions=[...],
    target_container=container or 'name')``."""

    def __init__(
        self,
        *,
        composable_node_descriptions: Iterable[Any],
        target_container: Any,
        condition: Condition | None = None,
    ) -> None:
        if isinstance(target_container, ExecuteNode):
            target: Any = target_container
        elif isinstance(target_container, str | SubstitutionLike | list | tuple):
            target = to_value(target_container)
        else:
            raise LaunchFileError(
                f"target_container is a {type(target_container).__name__}",
                here(),
                expected="a ComposableNodeContainer or the container's node name",
            )
        nodes = _descriptions(composable_node_descriptions)
        super().__init__(target, nodes, here(), condition)
