"""``$(param NAME [DEFAULT])``: a global parameter set by ``<set_parameter>``."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Param(Call):
    """The value of global parameter NAME (the last ``<set_parameter>`` in scope)."""

    NAME = "param"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "NAME [DEFAULT]"

    def perform(self, context: LaunchContext) -> str:
        """The parameter's value, or DEFAULT, or an error naming the parameter."""
        name = self.arg(0, context)
        for item in reversed(context.scope.global_params):
            if isinstance(item, tuple) and item[0] == name:
                return item[1]
        if len(self.args) > 1:
            return self.arg(1, context)
        raise self.fail(
            f"parameter '{name}' is not set", expected="a <set_parameter> for it in scope"
        )
