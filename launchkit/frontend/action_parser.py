"""The tag registry: which parser turns which XML tag into an action.

Every registered parser gets ``if``/``unless`` handled for it, and after it returns the
element is checked for attributes nobody read (an unknown attribute is an error, as in ROS).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from launchkit.description.conditions import Condition

if TYPE_CHECKING:
    from launchkit.description.actions.base import Action
    from launchkit.frontend.xml.entity import Entity
    from launchkit.frontend.xml.parser import XmlParser

TagParser = Callable[["Entity", "XmlParser"], "Action"]

TAGS: dict[str, TagParser] = {}


def tag(*names: str) -> Callable[[TagParser], TagParser]:
    """Register a parser for ``names`` (a tag and its alternative spellings)."""

    def register(function: TagParser) -> TagParser:
        for name in names:
            if name in TAGS:
                raise ValueError(f"tag <{name}> registered twice")
            TAGS[name] = function
        return function

    return register


def parse_condition(entity: Entity) -> Condition | None:
    """The ``if`` or ``unless`` attribute of any tag (both at once is an error)."""
    when, unless = entity.value("if"), entity.value("unless")
    if when is not None and unless is not None:
        raise entity.error(
            f"<{entity.tag}> has both 'if' and 'unless'",
            expected="at most one of them",
            attr="unless",
        )
    if when is not None:
        return Condition(when, False, entity.attribute_location("if"))
    if unless is not None:
        return Condition(unless, True, entity.attribute_location("unless"))
    return None
