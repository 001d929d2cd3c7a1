"""Parsers for the launch tags ROS 2's ``launch`` package defines (the ROS tags are in
``ros.py``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions import (
    AppendEnv,
    DeclareArgument,
    ExecuteProcess,
    Group,
    Include,
    IncludeArg,
    Keep,
    Log,
    ProcessOptions,
    Reset,
    ResetEnv,
    SetConfiguration,
    SetEnv,
    Shutdown,
    Timer,
    UnsetEnv,
)
from launchkit.description.actions.base import NameValueAction
from launchkit.description.actions.log import LEVELS
from launchkit.description.process_spec import OUTPUT_MODES
from launchkit.description.substitutions.base import Text

if TYPE_CHECKING:
    from launchkit.description.actions.base import Action
    from launchkit.frontend.action_parser import ActionParser, TagParser
    from launchkit.frontend.base_entity import Entity


def only_children(entity: Entity, allowed: tuple[str, ...]) -> list[Entity]:
    """``entity``'s children, all of which must be one of ``allowed`` tags."""
    children = entity.children()
    for child in children:
        if child.tag not in allowed:
            names = ", ".join(entity.label(t) for t in allowed)
            raise child.error(
                f"{child.label()} is not allowed inside {entity.label()}",
                expected=f"only {names} inside it" if allowed else "nothing inside it",
            )
    return children


def leaf(entity: Entity) -> Entity:
    """Check that ``entity`` has no children and hand it back."""
    only_children(entity, ())
    return entity


def parse_arg(entity: Entity, parser: ActionParser) -> Action:
    """``<arg name default description>`` with ``<choice value>`` children."""
    name = entity.plain("name")
    if not name:
        raise entity.error("<arg> is missing attribute 'name'", expected='name="..."')
    choices = []
    for child in only_children(entity, ("choice",)):
        value = child.plain("value")
        if value is None:
            raise child.error("<choice> is missing attribute 'value'", expected='value="..."')
        child.assert_fully_read()
        choices.append(value)
    return DeclareArgument(
        name,
        entity.value("default"),
        entity.plain("description") or "",
        tuple(choices),
    )


def name_value_parser(
    action: type[NameValueAction], name: str = "name", value: str = "value"
) -> TagParser:
    """The parser of a tag that is a name and a value and nothing else: ``<let name value>``,
    ``<set_env name value>``, ``<set_remap from to>`` (``name`` and ``value``: what the tag
    calls them)."""

    def parse(entity: Entity, parser: ActionParser) -> Action:
        leaf(entity)
        return action(entity.required(name), entity.required(value))

    return parse


def parse_keeps(entity: Entity, children: list[Entity]) -> list[Keep]:
    """``<keep name value/>`` children."""
    keeps = []
    for child in children:
        if child.tag == "keep":
            keeps.append(Keep(child.required("name"), child.required("value")))
            leaf(child).assert_fully_read()
    return keeps


def parse_group(entity: Entity, parser: ActionParser) -> Action:
    """``<group scoped forwarding>`` with ``<keep>`` and action children."""
    scoped = entity.static_bool("scoped", True)
    forwarding = entity.static_bool("forwarding", True)
    keeps = parse_keeps(entity, entity.children())
    machine = entity.value("machine")  # launchkit's extension: the host that runs it
    actions = parser.parse_actions(entity, skip=("keep",))
    return Group(actions, scoped, forwarding, keeps, machine=machine)


def parse_reset(entity: Entity, parser: ActionParser) -> Action:
    """``<reset>`` with ``<keep>`` children."""
    return Reset(parse_keeps(entity, only_children(entity, ("keep",))))


def parse_include(entity: Entity, parser: ActionParser) -> Action:
    """``<include file>`` with ``<arg name value/>`` children."""
    args = []
    for child in only_children(entity, ("arg",)):
        name = child.plain("name")
        value = child.value("value")
        if not name or value is None:
            raise child.error(
                "<arg> inside <include> needs 'name' and 'value'",
                expected='<arg name="..." value="..."/>',
            )
        leaf(child).assert_fully_read()
        args.append(IncludeArg(name, value))
    return Include(entity.required("file"), args)


#: The attributes ``<executable>`` and ``<node>`` share: (attribute, field of ProcessOptions,
#: how it is read: None for any value, a check of ``Entity.checked``, or the choices, and
#: whether a typed syntax may give it as a native value), in the order they are read.
_PROCESS_ATTRIBUTES: tuple[tuple[str, str, str | tuple[str, ...] | None, bool], ...] = (
    ("cwd", "cwd", None, True),
    ("name", "name", None, True),
    ("launch-prefix", "launch_prefix", None, True),
    ("output", "output", OUTPUT_MODES, True),
    ("shell", "shell", "bool", True),
    ("emulate_tty", "emulate_tty", "bool", True),
    ("sigterm_timeout", "sigterm_timeout", "ufloat", True),
    ("sigkill_timeout", "sigkill_timeout", "ufloat", True),
    ("respawn", "respawn", "bool", False),
    ("respawn_delay", "respawn_delay", "ufloat", True),
    ("respawn_max_retries", "respawn_max_retries", "int", True),
    ("on_exit", "on_exit", ("shutdown",), True),
)


def parse_process_options(entity: Entity) -> ProcessOptions:
    """The attributes and ``<env>`` children ``<executable>`` and ``<node>`` share."""
    options = ProcessOptions()
    for child in entity.children():
        if child.tag == "env":
            options.env.append((child.required("name"), child.required("value")))
            leaf(child).assert_fully_read()
    # only the attributes given are read (an unknown one's error lists those), in the table's
    # order (the first bad one in it is reported, however they are written)
    given = set(entity.attribute_names())
    for attribute, name, how, typed in _PROCESS_ATTRIBUTES:
        if attribute not in given:
            continue
        if how is None:
            value = entity.value(attribute)
        elif isinstance(how, tuple):
            value = entity.choice(attribute, how)
        else:
            value = entity.checked(attribute, how, typed=typed)
        setattr(options, name, value)
    return options


def parse_executable(entity: Entity, parser: ActionParser) -> Action:
    """``<executable cmd ...>`` with ``<env>`` children."""
    only_children(entity, ("env",))
    cmd = entity.required("cmd", 'cmd="program args..."')
    return ExecuteProcess(cmd, parse_process_options(entity))


def parse_timer(entity: Entity, parser: ActionParser) -> Action:
    """``<timer period cancel_on_shutdown>`` with action children."""
    period = entity.checked("period", "ufloat")
    if period is None:
        raise entity.error("<timer> is missing attribute 'period'", expected='period="SECONDS"')
    cancel = entity.static_bool("cancel_on_shutdown", True)
    return Timer(period, parser.parse_actions(entity), cancel)


def parse_unset_env(entity: Entity, parser: ActionParser) -> Action:
    """``<unset_env name>``."""
    leaf(entity)
    return UnsetEnv(entity.required("name"))


def parse_append_env(entity: Entity, parser: ActionParser) -> Action:
    """``<append_env name value prepend separator>``."""
    leaf(entity)
    return AppendEnv(
        entity.required("name"),
        entity.required("value"),
        entity.static_bool("prepend", False),
        entity.value("separator"),
    )


def parse_reset_env(entity: Entity, parser: ActionParser) -> Action:
    """``<reset_env/>``."""
    leaf(entity)
    return ResetEnv()


def parse_log(entity: Entity, parser: ActionParser) -> Action:
    """``<log message [level]>``."""
    leaf(entity)
    level = (entity.plain("level") or "INFO").upper()
    if level not in LEVELS:
        raise entity.error(
            f"<log> level is {level!r}", expected="one of " + ", ".join(LEVELS), attr="level"
        )
    return Log(entity.required("message"), level)


def parse_shutdown(entity: Entity, parser: ActionParser) -> Action:
    """``<shutdown reason>``."""
    leaf(entity)
    return Shutdown(entity.value("reason") or (Text(""),))


#: Tag name -> parser: the launch tags.
TAGS: dict[str, TagParser] = {
    "arg": parse_arg,
    "let": name_value_parser(SetConfiguration),
    "group": parse_group,
    "reset": parse_reset,
    "include": parse_include,
    "executable": parse_executable,
    "timer": parse_timer,
    "set_env": name_value_parser(SetEnv),
    "unset_env": parse_unset_env,
    "append_env": parse_append_env,
    "reset_env": parse_reset_env,
    "log": parse_log,
    "shutdown": parse_shutdown,
}


def register(parser: ActionParser) -> None:
    """Have ``parser`` read the launch tags."""
    for name, parse in TAGS.items():
        parser.register(name, parse)
