"""``<arg>``: declare a launch argument with a default, a description and choices."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Value, describe, perform
from launchkit.errors import LaunchArgumentError, Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class DeclareArgument(Action):
    """Set configuration NAME to its default unless something set it already; check choices."""

    TAG = "arg"

    def __init__(
        self,
        name: str,
        default: Value | None = None,
        description: str = "",
        choices: tuple[str, ...] = (),
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.name = name
        self.default = default
        self.description = description
        self.choices = choices

    def execute(self, context: LaunchContext) -> None:
        """Apply the default if needed, then validate the value against the choices."""
        if self.name not in context.configurations:
            if self.default is None:
                raise self.missing_error()
            context.configurations[self.name] = perform(self.default, context)
        self.check_choice(context.configurations[self.name])

    def check_choice(self, value: str) -> None:
        """Raise unless ``value`` is one of the choices (when there are any)."""
        if self.choices and value not in self.choices:
            raise LaunchArgumentError(
                f"argument '{self.name}' got {value!r}",
                self.location,
                expected="one of " + ", ".join(repr(c) for c in self.choices),
            )

    def missing_error(self) -> LaunchArgumentError:
        """The error for this required argument being absent."""
        about = f" ({self.description})" if self.description else ""
        return LaunchArgumentError(
            f"required argument '{self.name}'{about} was not given",
            self.location,
            expected=f"{self.name}:=VALUE on the command line or an <arg> in the <include>",
        )

    def describe_default(self) -> str | None:
        """The default as written, or None when the argument is required."""
        return None if self.default is None else describe(self.default)
