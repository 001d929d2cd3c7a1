"""The action protocol: what one tag does when the launch reaches it."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, TypeVar

from launchkit.description.conditions import Condition
from launchkit.description.events import ExecutionComplete
from launchkit.description.substitutions.base import Value, perform
from launchkit.description.truth import BOOL_EXPECTED, bool_value
from launchkit.errors import LaunchFileError, LaunchkitError, Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext

T = TypeVar("T")


class Action:
    """Base of every tag's action: ``visit`` checks ``if``/``unless``, then ``execute``."""

    TAG = ""
    #: Whether the action completes later than when it runs (a process when it exits for
    #: good, a timer when it fires); those emit ExecutionComplete themselves.
    COMPLETES_LATER = False

    def __init__(self, location: Location | None = None, condition: Condition | None = None):
        self.location = location
        # a Python file's condition is anything with evaluate(context), as in ROS
        if condition is not None and not callable(getattr(condition, "evaluate", None)):
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


class NameAction(Action):
    """An action on one name (``<unset_env>``, Python's ``UnsetLaunchConfiguration``): it
    performs the name, then :meth:`apply` does what the tag says with it."""

    def __init__(
        self, name: Value, location: Location | None = None, condition: Condition | None = None
    ) -> None:
        super().__init__(location, condition)
        self.name = name

    def execute(self, context: LaunchContext) -> None:
        """Perform the name and apply it."""
        self.apply(context, perform(self.name, context))

    def apply(self, context: LaunchContext, name: str) -> None:
        """Do what the tag says with the performed name."""
        raise NotImplementedError


class NameValueAction(Action):
    """An action on a name and a value (``<let>``, ``<set_env>``, ``<set_parameter>``,
    ``<set_remap>``): it performs both, then :meth:`apply` stores them where the tag says."""

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
        """Perform the name and the value and apply them."""
        self.apply(context, perform(self.name, context), perform(self.value, context))

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Store the performed pair where the tag says."""
        raise NotImplementedError


def typed_float(value: Value, context: LaunchContext, what: str, loc: Location | None) -> float:
    """``value`` performed and read as a number; an error naming ``what`` otherwise."""
    return _converted(value, context, what, loc, float, "a number")


def typed_int(value: Value, context: LaunchContext, what: str, loc: Location | None) -> int:
    """``value`` performed and read as an integer."""
    return _converted(value, context, what, loc, int, "an integer")


def typed_bool(value: Value, context: LaunchContext, what: str, loc: Location | None) -> bool:
    """``value`` performed and read as a boolean (YAML spellings)."""
    return _converted(value, context, what, loc, _boolean, BOOL_EXPECTED)


def _converted(
    value: Value,
    context: LaunchContext,
    what: str,
    loc: Location | None,
    convert: Callable[[str], T],
    expected: str,
) -> T:
    """``value`` performed and converted; an error naming ``what`` when ``convert`` refuses
    the text (ValueError)."""
    text = perform(value, context)
    try:
        return convert(text)
    except ValueError:
        raise RuntimeLaunchError(f"{what} is {text!r}", loc, expected=expected) from None


def _boolean(text: str) -> bool:
    result = bool_value(text)
    if result is None:
        raise ValueError(text)
    return result
