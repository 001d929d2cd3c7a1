"""``<set_env>``, ``<unset_env>``, ``<append_env>``, ``<reset_env>``: the launch's environment."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action, NameAction, NameValueAction
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class SetEnv(NameValueAction):
    """Set variable NAME to VALUE for later processes in scope."""

    TAG = "set_env"

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Set it."""
        context.environment[name] = value


class UnsetEnv(NameAction):
    """Remove variable NAME."""

    TAG = "unset_env"

    def apply(self, context: LaunchContext, name: str) -> None:
        """Remove it (no error when it was not set)."""
        context.environment.pop(name, None)


class AppendEnv(NameValueAction):
    """Append (or prepend) VALUE to variable NAME with SEPARATOR; set it when unset."""

    TAG = "append_env"

    def __init__(
        self,
        name: Value,
        value: Value,
        prepend: bool = False,
        separator: Value | None = None,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(name, value, location, condition)
        self.prepend = prepend
        self.separator = separator

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Append or prepend."""
        sep = os.pathsep if self.separator is None else perform(self.separator, context)
        current = context.environment.get(name)
        if current:
            value = value + sep + current if self.prepend else current + sep + value
        context.environment[name] = value


class ResetEnv(Action):
    """Put the environment back to what the launch started with."""

    TAG = "reset_env"

    def execute(self, context: LaunchContext) -> None:
        """Reset it."""
        context.environment.clear()
        context.environment.update(context.initial_environment)
