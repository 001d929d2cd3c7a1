"""The action protocol: what one tag does when the launch reaches it."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from launchkit.description.conditions import Condition
from launchkit.description.events import ExecutionComplete
from launchkit.description.substitutions.base import Value, perform
from launchkit.description.truth import BOOL_EXPECTED, bool_value
from launchkit.errors import LaunchFileError, LaunchkitError, Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Action:
    """Base of every tag's action: ``visit`` checks ``if``/``unless``, then ``execute``."""

    TAG = ""
    #: Whether the action completes later than when it runs (a process when it exits for
    #: good, a timer when it fires); those emit ExecutionComplete themselves.
    COMPLETES_LATER = False

    def __init__(self, location: Location | None = None, condition: Condition | None = None):
        self.location = location
        if condition is not None and not isinstance(condition, Condition):  # a Python file's
            raise LaunchFileError(
                f"the condition of {type(self).__name__} is a {type(condition).__name__}, "
                "not a condition",
                location,
                expected="IfCondition(...), UnlessCondition(...) or LaunchConfigurationEquals(...)",
            )
        self.condition = condition

    def visit(self, context: LaunchContext) -> None:
        """Run this action unless its condition says not to; errors get its location."""
        try:
            if self.condition is not None and not self.condition.evaluate(context):
                return
            self.execute(context)
            if not self.COMPLETES_LATER and context.delivers_events:
                context.emit(ExecutionComplete(action=self))
        except LaunchkitError as error:
            if self.location is not None:
                error.with_location(self.location)
            raise

    def execute(self, context: LaunchContext) -> None:
        """Do what the tag says."""
        raise NotImplementedError

    def children(self) -> Sequence[Action]:
        """Nested actions (for walking the tree without running it)."""
        return ()

    def __repr__(self) -> str:
        fields = {k: v for k, v in vars(self).items() if k not in ("location",) and v is not None}
        return f"{type(self).__name__}({fields})"


def typed_float(value: Value, context: LaunchContext, what: str, loc: Location | None) -> float:
    """``value`` performed and read as a number; an error naming ``what`` otherwise."""
    text = perform(value, context)
    try:
        return float(text)
    except ValueError:
        raise RuntimeLaunchError(f"{what} is {text!r}", loc, expected="a number") from None


def typed_int(value: Value, context: LaunchContext, what: str, loc: Location | None) -> int:
    """``value`` performed and read as an integer."""
    text = perform(value, context)
    try:
        return int(text)
    except ValueError:
        raise RuntimeLaunchError(f"{what} is {text!r}", loc, expected="an integer") from None


def typed_bool(value: Value, context: LaunchContext, what: str, loc: Location | None) -> bool:
    """``value`` performed and read as a boolean (YAML spellings)."""
    text = perform(value, context)
    result = bool_value(text)
    if result is None:
        raise RuntimeLaunchError(f"{what} is {text!r}", loc, expected=BOOL_EXPECTED)
    return result
