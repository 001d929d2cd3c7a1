"""``if`` and ``unless``: whether an action runs."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._record import Frozen, slot_setters
from launchkit.description.substitutions.base import Text, Value, describe, perform
from launchkit.description.truth import CONDITION_EXPECTED, condition_value
from launchkit.errors import Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


#: The usual spellings, looked up before the full rule (a large file evaluates one per action).
_SPELLED = {"true": True, "1": True, "false": False, "0": False}


class Condition(Frozen):
    """``if="VALUE"`` (or ``unless`` when ``negate``), evaluated with the strict rule;
    ``location`` is where its error points (None where none is known, or can be: a literal
    ``true``, ``1``, ``false`` or ``0``)."""

    __slots__ = ("location", "negate", "value")
    value: Value
    negate: bool
    location: Location | None

    def __init__(self, value: Value, negate: bool, location: Location | None = None) -> None:
        _set_value(self, value)
        _set_negate(self, negate)
        _set_location(self, location)

    def evaluate(self, context: LaunchContext) -> bool:
        """Whether the guarded action runs; an error for anything but true/1/false/0."""
        value = self.value
        if len(value) == 1 and type(value[0]) is Text:  # the usual literal (a call shorter)
            text = value[0].text
        else:
            text = perform(value, context)
        result = _SPELLED.get(text)
        if result is None:
            result = condition_value(text)
        if result is None:
            attr = "unless" if self.negate else "if"
            raise RuntimeLaunchError(
                f"invalid {attr} condition {text!r} (from {describe(self.value)!r})",
                self.location,
                expected=CONDITION_EXPECTED,
            )
        return not result if self.negate else result


_set_value, _set_negate, _set_location = slot_setters(Condition)
