"""A parsed launch file: its actions and the arguments it declares."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from launchkit.description.actions.arg import DeclareArgument
from launchkit.description.actions.base import Action
from launchkit.description.actions.group import Group


@dataclass
class LaunchDescription:
    """The actions of one launch file, in document order."""

    path: Path
    actions: list[Action] = field(default_factory=list)
    deprecated: str | None = None

    def declared_arguments(self) -> list[DeclareArgument]:
        """Every ``<arg>`` of this file (inside groups too), in document order."""
        return [a for a in walk(self.actions) if isinstance(a, DeclareArgument)]

    def required_arguments(self) -> list[DeclareArgument]:
        """``<arg>``s without a default that are reached unconditionally at the top level."""
        found: list[DeclareArgument] = []
        outer: list[Iterator[Action]] = []  # the groups being scanned (no recursion)
        actions = iter(self.actions)
        while True:
            for action in actions:
                if action.condition is not None:
                    continue
                if isinstance(action, DeclareArgument):
                    if action.default is None:
                        found.append(action)
                elif isinstance(action, Group) and action.forwarding:
                    outer.append(actions)
                    actions = iter(action.actions)
                    break
            else:
                if not outer:
                    return found
                actions = outer.pop()


def walk(actions: list[Action]) -> list[Action]:
    """Every action in ``actions`` and their children, depth first, in document order."""
    out: list[Action] = []
    append = out.append
    outer: list[Iterator[Action]] = []  # the lists being walked around this one (no recursion)
    level: Iterator[Action] = iter(actions)
    while True:
        for action in level:
            append(action)
            children = action.children()
            if children:
                outer.append(level)
                level = iter(children)
                break
        else:
            if not outer:
                return out
            level = outer.pop()
