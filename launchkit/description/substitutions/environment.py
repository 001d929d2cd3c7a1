"""``$(env NAME [DEFAULT])``: the launch's environment (after ``<set_env>`` and friends)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Env(Call):
    """Environment variable NAME of the launch, or DEFAULT (``$(env X '')`` is "optenv")."""

    NAME = "env"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "NAME [DEFAULT]"

    def perform(self, context: LaunchContext) -> str:
        """The variable's value, or DEFAULT, or an error naming the variable."""
        name = self.arg(0, context)
        value = context.environment.get(name)
        if value is not None:
            return value
        if len(self.args) > 1:
            return self.arg(1, context)
        raise self.fail(
            f"environment variable '{name}' is not set",
            expected=f"{name} in the environment, or $(env {name} DEFAULT)",
        )
