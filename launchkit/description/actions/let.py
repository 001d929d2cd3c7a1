"""``<let>``: set a launch configuration in the current scope."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions.base import NameValueAction

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class SetConfiguration(NameValueAction):
    """Set configuration NAME to VALUE (overwriting CLI values, as ROS does)."""

    TAG = "let"

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Set it."""
        context.configurations[name] = value
