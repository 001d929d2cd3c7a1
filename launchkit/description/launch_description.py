"""A parsed launch file: its actions and the arguments it declares."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from launchkit._record import Record
from launchkit.description.actions.arg import DeclareArgument
from launchkit.description.actions.base import Action
from launchkit.description.actions.group import Group


class LaunchDescription(Record):
    """The actions of one launch file, in document order."""

    __slots__ = ("actions", "deprecated", "path")
    path: Path
    actions: list[Action]
    deprecated: str | None

    def __init__(
        self, path: Path, actions: list[Action] | None = None, deprecated: str | None = None
    ) -> None:
        self.path = path
        self.actions = [] if actions is None else actions
        self.deprecated = deprecated

    def declared_arguments(self) -> list[DeclareArgument]:
        """Every ``<arg>`` of this file (inside groups too), in document order."""
        return [a for a in walk(self.actions) if isinstance(a, DeclareArgument)]

    def required_arguments(self) -> list[DeclareArgument]:
        """``<arg>``s without a default that are reached unconditionally at the top level."""
        found: list[DeclareArgument] = []
        pending = self.actions[::-1]  # a stack, next action last (pop(0) is quadratic)
        while pending:
            action = pending.pop()
            if action.condition is not None:
                continue
            if isinstance(action, DeclareArgument) and action.default is None:
                found.append(action)
            elif isinstance(action, Group) and action.forwarding:
                pending.extend(reversed(action.actions))
        return found


def walk(actions: list[Action]) -> list[Action]:
    """Every action in ``actions`` and their children, depth first, in document order."""
    out: list[Action] = []
    pending = actions[::-1]  # a stack, next action last: no recursion, linear
    while pending:
        action = pending.pop()
        out.append(action)
        children = action.children()
        if children:
            pending.extend(reversed(children))
    return out


def walk_lazily(actions: list[Action]) -> Iterator[Action]:
    """:func:`walk` one action at a time (for a search that may stop at the first)."""
    pending = actions[::-1]
    while pending:
        action = pending.pop()
        yield action
        children = action.children()
        if children:
            pending.extend(reversed(children))
