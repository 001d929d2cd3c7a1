"""``LocalSubstitution('event.reason')``: a local of the launch context (the event an event
handler is reacting to), read by a dotted path of attribute names, never evaluated."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Substitution
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Local(Substitution):
    """The value at ``expression`` (``name.attr.attr``) among the context's locals, as text
    (bytes decoded, booleans lower-case)."""

    def __init__(
        self, expression: str, description: str | None = None, location: Location | None = None
    ) -> None:
        self.expression = expression
        self.description = description
        self.location = location

    def perform(self, context: LaunchContext) -> str:
        """Look the path up."""
        name, *attributes = self.expression.split(".")
        if name not in context.locals:
            known = ", ".join(sorted(context.locals)) or "none here"
            raise self.fail(
                f"local '{name}' does not exist (in {self.expression!r})",
                expected=f"one of the context's locals ({known}); 'event' exists only in "
                "the actions of an event handler",
            )
        value: object = context.locals[name]
        for attribute in attributes:
            try:
                value = getattr(value, attribute)
            except AttributeError:
                raise self.fail(
                    f"{type(value).__name__} has no attribute '{attribute}' "
                    f"(in {self.expression!r})",
                    expected="a path of attribute names such as 'event.reason'",
                ) from None
        if isinstance(value, bytes):
            return value.decode(errors="replace")
        if isinstance(value, bool):
            return str(value).lower()
        return str(value)

    def describe(self) -> str:
        """``LocalVar('...')`` as ROS writes it."""
        return f"LocalVar('{self.description or self.expression}')"
