"""``if`` and ``unless``: whether an action runs."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Value, describe, perform
from launchkit.description.truth import CONDITION_EXPECTED, condition_value
from launchkit.errors import Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


@dataclass(frozen=True)
class Condition:
    """``if="VALUE"`` (or ``unless`` when ``negate``), evaluated with the strict rule;
    ``location`` is where its error points."""

    value: Value
    negate: bool
    location: Location | None = None

    def evaluate(self, context: LaunchContext) -> bool:
        """Whether the guarded action runs; an error for anything but true/1/false/0."""
        text = perform(self.value, context)
        result = condition_value(text)
        if result is None:
            attr = "unless" if self.negate else "if"
            raise RuntimeLaunchError(
                f"invalid {attr} condition {text!r} (from {describe(self.value)!r})",
                self.location,
                expected=CONDITION_EXPECTED,
            )
        return not result if self.negate else result
