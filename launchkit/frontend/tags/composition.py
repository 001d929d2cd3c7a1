"""Parsers for launch_ros's composition tags: ``<node_container>``, ``<load_composable_node>``
and their ``<composable_node>`` children."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions import ParamValue, Remap
from launchkit.description.actions.composition import (
    ComposableNode,
    ComposableNodeContainer,
    LoadComposableNodes,
)
from launchkit.frontend.action_parser import parse_condition
from launchkit.frontend.tags.launch import leaf, only_children
from launchkit.frontend.tags.ros import parse_node, parse_param

if TYPE_CHECKING:
    from launchkit.description.actions.base import Action
    from launchkit.frontend.action_parser import ActionParser, TagParser
    from launchkit.frontend.base_entity import Entity


def parse_composable_node(entity: Entity) -> ComposableNode:
    """``<composable_node pkg plugin name [namespace] [if|unless]>`` with ``<param>``,
    ``<remap>`` and ``<extra_arg name value>`` children."""
    children = only_children(entity, ("param", "remap", "extra_arg"))
    node = ComposableNode(
        package=entity.required("pkg", 'pkg="PACKAGE"'),
        plugin=entity.required("plugin", 'plugin="pkg::Class"'),
        name=entity.required("name", 'name="NODE NAME"'),
        namespace=entity.value("namespace"),
        condition=parse_condition(entity),
        location=entity.location,
    )
    for child in children:
        if child.tag == "param":
            node.params.append(parse_param(child))
        elif child.tag == "remap":
            node.remaps.append(Remap(child.required("from"), child.required("to")))
            leaf(child).assert_fully_read()
        else:
            value = child.required("value")
            node.extra_arguments.append(ParamValue(child.required("name"), value))
            leaf(child).assert_fully_read()
    entity.assert_fully_read()
    return node


def parse_node_container(entity: Entity, parser: ActionParser) -> Action:
    """``<node_container pkg exec name namespace ...>``: a ``<node>`` whose children are
    ``<composable_node>``s (besides ``<param>``, ``<remap>``, ``<env>``)."""
    nodes = [c for c in entity.children() if c.tag == "composable_node"]
    only_children(entity, ("param", "remap", "env", "composable_node"))
    container = parse_node(entity, parser, skip=("composable_node",))
    assert isinstance(container, ComposableNodeContainer)
    container.nodes = [parse_composable_node(n) for n in nodes]
    return container


def parse_load_composable_node(entity: Entity, parser: ActionParser) -> Action:
    """``<load_composable_node target="CONTAINER">`` with ``<composable_node>`` children."""
    children = only_children(entity, ("composable_node",))
    target = entity.required("target", 'target="CONTAINER NODE NAME"')
    return LoadComposableNodes(target, [parse_composable_node(c) for c in children])


#: Tag name -> parser: the composition tags of launch_ros.
TAGS: dict[str, TagParser] = {
    "node_container": parse_node_container,
    "load_composable_node": parse_load_composable_node,
}


def register(parser: ActionParser) -> None:
    """Have ``parser`` read the composition tags."""
    for name, parse in TAGS.items():
        parser.register(name, parse)
