"""Parsers for the tags ROS 2's ``launch_ros`` package defines."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions import (
    ExecuteNode,
    ParamFile,
    ParamGroup,
    ParamValue,
    PushRosNamespace,
    Remap,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
    SetUseSimTime,
)
from launchkit.description.actions.composition import ComposableNodeContainer
from launchkit.description.actions.parameters import PARAM_TYPES, ParamEntry
from launchkit.frontend.tags.launch import (
    leaf,
    name_value_parser,
    only_children,
    parse_process_options,
)

if TYPE_CHECKING:
    from launchkit.description.actions.base import Action
    from launchkit.frontend.action_parser import ActionParser, TagParser
    from launchkit.frontend.base_entity import Entity


def parse_param(entity: Entity) -> ParamValue | ParamGroup | ParamFile:
    """``<param>``: name+value [type, value-sep], name + nested params, or from [allow_substs]."""
    source = entity.value("from")
    name = entity.value("name")
    if source is not None:
        if name is not None:
            raise entity.error(
                "<param> has both 'from' and 'name'",
                expected="either from=FILE or name=...",
                attr="name",
            )
        leaf(entity)
        allow = entity.static_bool("allow_substs", False)
        entity.assert_fully_read()
        return ParamFile(source, allow, entity.location)
    if name is None:
        raise entity.error(
            "<param> needs 'name' or 'from'",
            expected=f"{entity.example('name')} and {entity.example('value')}",
        )
    kind = entity.plain("type")
    if kind is not None and kind not in PARAM_TYPES:
        raise entity.error(
            f"<param> type is {kind!r}", expected="one of " + ", ".join(PARAM_TYPES), attr="type"
        )
    typed = entity.param_value("value", kind)
    value, kind = (None, kind) if typed is None else typed
    children = only_children(entity, ("param",))
    if value is not None and children:
        raise entity.error(
            "<param> has both a value and nested <param>s", expected="one or the other"
        )
    if value is None:
        if not children:
            raise entity.error(
                "<param> has no value", expected='value="..." or nested <param> elements'
            )
        if kind is not None:
            raise entity.error(
                "<param> has both a type and nested <param>s",
                expected="a type only with a value",
                attr="type",
            )
        entity.assert_fully_read()
        return ParamGroup(name, [_no_file(c, parse_param(c)) for c in children])
    sep = entity.value("value-sep") if entity.SPLITS_LISTS else None
    entity.assert_fully_read()
    return ParamValue(name, value, kind, sep, entity.location)


def _no_file(entity: Entity, param: ParamValue | ParamGroup | ParamFile) -> ParamValue | ParamGroup:
    if isinstance(param, ParamFile):
        raise entity.error("a nested <param> cannot use 'from'", expected="name and value")
    return param


def parse_node(entity: Entity, parser: ActionParser, skip: tuple[str, ...] = ()) -> Action:
    """``<node pkg exec name namespace exec_name args ros_args ...>`` with ``<param>``,
    ``<remap>`` and ``<env>`` children (``skip``: children another parser reads; their tag
    also makes the node a ``<node_container>``)."""
    allowed = ("param", "remap", "env")
    children = [c for c in only_children(entity, allowed + skip) if c.tag in allowed]
    params: list[ParamEntry] = [parse_param(c) for c in children if c.tag == "param"]
    remaps = []
    for child in children:
        if child.tag == "remap":
            remaps.append(Remap(child.required("from"), child.required("to")))
            leaf(child).assert_fully_read()
    node_name = entity.value("name")
    options = parse_process_options(entity)
    options.name = None  # `name` is the ROS node name here, not the process label
    kind = ComposableNodeContainer if skip else ExecuteNode
    return kind(
        entity.value("pkg"),
        entity.required("exec", 'exec="EXECUTABLE"'),
        options,
        node_name=node_name,
        namespace=entity.value("namespace"),
        exec_name=entity.value("exec_name"),
        args=entity.value("args"),
        ros_args=entity.value("ros_args"),
        params=params,
        remaps=remaps,
    )


def parse_push_ros_namespace(entity: Entity, parser: ActionParser) -> Action:
    """``<push_ros_namespace namespace>``."""
    leaf(entity)
    return PushRosNamespace(entity.required("namespace"))


def parse_set_parameters_from_file(entity: Entity, parser: ActionParser) -> Action:
    """``<set_parameters_from_file filename>``."""
    leaf(entity)
    return SetParametersFromFile(entity.required("filename"))


def parse_set_use_sim_time(entity: Entity, parser: ActionParser) -> Action:
    """``<set_use_sim_time value>``."""
    leaf(entity)
    value = entity.checked("value", "bool", typed=False)  # ROS's YAML reader: text only
    if value is None:
        raise entity.error(
            "<set_use_sim_time> is missing attribute 'value'", expected='value="true"'
        )
    return SetUseSimTime(value)


#: Tag name -> parser: the launch_ros tags.
TAGS: dict[str, TagParser] = {
    "node": parse_node,
    "push_ros_namespace": parse_push_ros_namespace,
    "push-ros-namespace": parse_push_ros_namespace,
    "set_parameter": name_value_parser(SetParameter),
    "set_parameters_from_file": parse_set_parameters_from_file,
    "set_remap": name_value_parser(SetRemap, "from", "to"),
    "set_use_sim_time": parse_set_use_sim_time,
}


def register(parser: ActionParser) -> None:
    """Have ``parser`` read the launch_ros tags."""
    for name, parse in TAGS.items():
        parser.register(name, parse)
