"""Entities to actions, the same for every syntax: which parser reads which tag.

An :class:`ActionParser` holds a table of tag parsers that the tag modules fill explicitly
(``frontend/tags``: each has a ``register``), and does what every tag shares: ``if``/``unless``,
the action's location, and the check that no attribute was left unread (an unknown attribute
is an error, as in ROS).
"""

from __future__ import annotations

from collections.abc import Callable

from launchkit.description.actions.base import Action
from launchkit.description.conditions import Condition
from launchkit.errors import did_you_mean
from launchkit.frontend.base_entity import Entity

#: How deep actions may nest (a group in a group ...; real files nest a few levels): parsing
#: and evaluating recurse once per level.
MAX_NESTING = 100

#: Parses one tag's entity into its action; the parser is there for nested actions.
TagParser = Callable[[Entity, "ActionParser"], Action]

_ROS1_HINTS = {
    "rosparam": 'ROS 2 has no <rosparam>; use <param from="file.yaml"/> inside <node>',
    "machine": "ROS 2 has no <machine>",
    "test": "ROS 2 has no <test>; see launchkit.testing",
    "env": "use <set_env> at this level; <env> belongs inside <executable> or <node>",
}


class ActionParser:
    """Parses entities of any syntax into actions with the tag parsers registered on it."""

    def __init__(self) -> None:
        self._parsers: dict[str, TagParser] = {}
        self._depth = 0  # actions open around the one being parsed

    def register(self, name: str, parser: TagParser) -> None:
        """Have ``parser`` read tag ``name``; a tag registered twice is a programming error."""
        if name in self._parsers:
            raise ValueError(f"tag <{name}> registered twice")
        self._parsers[name] = parser

    def tags(self) -> list[str]:
        """Every tag name this parser reads, sorted."""
        return sorted(self._parsers)

    def parse_actions(self, parent: Entity, skip: tuple[str, ...] = ()) -> list[Action]:
        """The actions among ``parent``'s children (tags in ``skip`` are left to the parent)."""
        return [self.parse_action(child) for child in parent.children() if child.tag not in skip]

    def parse_action(self, entity: Entity) -> Action:
        """One action tag, with its condition, fully checked."""
        parse = self._parsers.get(entity.tag)
        if parse is None:
            raise entity.error(
                f"unknown tag {entity.label()}",
                expected="one of: " + ", ".join(self.tags()),
                hint=_ROS1_HINTS.get(entity.tag) or did_you_mean(entity.tag, self.tags()),
            )
        condition = parse_condition(entity)
        if self._depth >= MAX_NESTING:
            raise entity.error(
                f"actions nested deeper than {MAX_NESTING}",
                expected=f"at most {MAX_NESTING} levels of <group>, <timer>, ... in one another",
            )
        self._depth += 1
        try:
            action = parse(entity, self)
        finally:
            self._depth -= 1
        action.condition = condition
        action.location = entity.location
        entity.assert_fully_read()
        return action


def parse_condition(entity: Entity) -> Condition | None:
    """The ``if`` or ``unless`` attribute of any tag (both at once is an error)."""
    when, unless = entity.value("if"), entity.value("unless")
    if when is not None and unless is not None:
        raise entity.error(
            f"{entity.label()} has both 'if' and 'unless'",
            expected="at most one of them",
            attr="unless",
        )
    if when is not None:
        return Condition(when, False, entity.attribute_location("if"))
    if unless is not None:
        return Condition(unless, True, entity.attribute_location("unless"))
    return None
