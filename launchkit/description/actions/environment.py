"""``<set_env>``, ``<unset_env>``, ``<append_env>``, ``<reset_env>``: the launch's environment."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class SetEnv(Action):
    """Set variable NAME to VALUE for later processes in scope."""

    TAG = "set_env"

    def __init__(
        self,
        name: Value,
        value: Value,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.name = name
        self.value = value

    def execute(self, context: LaunchContext) -> None:
        """Set it."""
        context.environment[perform(self.name, context)] = perform(self.value, context)


class UnsetEnv(Action):
    """Remove variable NAME."""

    TAG = "unset_env"

    def __init__(
        self, name: Value, location: Location | None = None, condition: Condition | None = None
    ) -> None:
        super().__init__(location, condition)
        self.name = name

    def execute(self, context: LaunchContext) -> None:
        """Remove it (no error when it was not set)."""
        context.environment.pop(perform(self.name, context), None)


class AppendEnv(Action):
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
        super().__init__(location, condition)
        self.name = name
        self.value = value
        self.prepend = prepend
        self.separator = separator

    def execute(self, context: LaunchContext) -> None:
        """Append or prepend."""
        name = perform(self.name, context)
        value = perform(self.value, context)
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
