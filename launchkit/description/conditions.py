"""``if`` and ``unless``: whether an action runs."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._record import Frozen, slot_setters
from launchkit.description.substitutions.base import Text, Value, describe, perform
from launchkit.description.truth import CONDITION_EXPECTED, condition_value
from launchkit.errors import DeferredLocation, Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


#: The usual spellings, looked up before the full rule (a large file evaluates one per action).
_SPELLED = {"true": True, "1": True, "false": False, "0": False}


class Condition(Frozen):
    """``if="VALUE"`` (or ``unless`` when ``negate``), evaluated with the strict rule.

    Its ``location`` may be given deferred (see :data:`~launchkit.errors.DeferredLocation`):
    it is then found when first asked for (an error, a comparison), as a large XML file's
    conditions are, most of which are never asked."""

    __slots__ = ("negate", "value", "where")
    value: Value
    negate: bool
    where: Location | DeferredLocation | None

    def __init__(
        self, value: Value, negate: bool, location: Location | DeferredLocation | None = None
    ) -> None:
        _set_value(self, value)
        _set_negate(self, negate)
        _set_where(self, location)

    @property
    def location(self) -> Location | None:
        """Where the condition is written."""
        where = self.where
        if type(where) is tuple:
            where = where[0](*where[1:])
            _set_where(self, where)
        return where  # type: ignore[return-value]

    def __reduce__(self) -> tuple[object, ...]:
        return Condition, (self.value, self.negate, self.location)

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


_set_value, _set_negate, _set_where = slot_setters(Condition)
# compared, hashed and shown with its location found (the same deferred or not)
Condition.field_names = ("value", "negate", "location")
