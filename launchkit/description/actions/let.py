"""``<let>``: set a launch configuration in the current scope."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class SetConfiguration(Action):
    """Set configuration NAME to VALUE (overwriting CLI values, as ROS does)."""

    TAG = "let"

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
        """Perform name and value, then set it."""
        context.configurations[perform(self.name, context)] = perform(self.value, context)
