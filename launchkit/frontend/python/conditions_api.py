"""Stand-ins for ``launch.Condition`` and ``launch.conditions``.

As in ROS, a condition is an object whose ``evaluate(context)`` says whether an action runs:
``launch.Condition(predicate=f)`` calls ``f(context)``, and ``IfCondition`` & co. are its
subclasses. The actions only call ``evaluate``; launchkit calls it with its own context, which
this module turns into the context launch files see (:class:`LaunchContextView`) before a
launch file's code gets it, so a class of the launch file's own (nav2_common's
``ReplaceString`` takes one and calls ``condition.evaluate(context)`` itself) sees what it
would see under ROS.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

from launchkit.description.conditions import Condition as LaunchkitCondition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions.base import Substitution, Value, describe, perform
from launchkit.frontend.python.values import (
    call_user,
    context_view,
    current_modules,
    function_name,
    here,
    optional_value,
    to_value,
)


def _call(condition: Any, function: Callable[..., Any], *args: Any) -> bool:
    """``function(*args, context)``: a launch file's own code deciding ``condition`` (not
    called while ``--print`` shows an event handler's actions: the action is shown)."""
    view = context_view(args[-1])
    preview = view.real.instead_of_calling
    if preview is not None:
        preview(f"{function_name(function)} (a condition)", getattr(condition, "location", None))
        return True
    modules = getattr(condition, "_modules", None) or current_modules()
    return bool(call_user(function, "condition", modules, *args[:-1], view))


def _launch_files_evaluate(evaluate: Callable[[Any, Any], bool]) -> Callable[[Any, Any], bool]:
    @functools.wraps(evaluate)
    def wrapper(self: Any, context: Any) -> bool:
        return _call(self, evaluate, self, context)

    return wrapper


class Condition:
    """``launch.Condition(predicate=None)``: ``evaluate(context)`` is ``predicate(context)``,
    False without one. A launch file's subclass's own ``evaluate`` gets the context launch
    files see too."""

    def __init__(self, *, predicate: Callable[[Any], bool] | None = None) -> None:
        self._predicate = predicate
        self._modules = current_modules()
        self.location = here()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "evaluate" in cls.__dict__ and cls.__module__ != __name__:  # a launch file's own
            own = _launch_files_evaluate(cls.__dict__["evaluate"])
            cls.evaluate = own  # type: ignore[method-assign,assignment]

    def evaluate(self, context: Any) -> bool:
        """Whether the guarded action runs."""
        if self._predicate is None:
            return False
        return _call(self, self._predicate, context)

    def describe(self) -> str:
        """``repr``, as ROS's base class says."""
        return repr(self)


class _Wrapping(Condition):
    """A condition launchkit evaluates itself (``inner``), strictly as ROS does."""

    def __init__(self, inner: LaunchkitCondition) -> None:
        super().__init__()
        self.inner = inner

    def evaluate(self, context: Any) -> bool:
        """What ``inner`` says in the launch's context."""
        return self.inner.evaluate(context_view(context).real)

    def describe(self) -> str:
        """How it was written."""
        return f"{type(self).__name__}({describe(self.inner.value)!r})"


class IfCondition(_Wrapping):
    """``launch.conditions.IfCondition``: true for ``true`` or ``1``, false for ``false`` or
    ``0`` (any case, spaces around ignored), an error for anything else."""

    def __init__(self, predicate_expression: Any) -> None:
        super().__init__(LaunchkitCondition(to_value(predicate_expression), False, here()))


class UnlessCondition(_Wrapping):
    """``launch.conditions.UnlessCondition``: IfCondition negated."""

    def __init__(self, predicate_expression: Any) -> None:
        super().__init__(LaunchkitCondition(to_value(predicate_expression), True, here()))


class _ConfigurationEquals(Substitution):
    """``true`` when configuration ``name`` is exactly ``expected`` (text), or is unset and
    ``expected`` is None: ROS's LaunchConfigurationEquals test."""

    def __init__(self, name: str, expected: Value | None, negate: bool) -> None:
        self.name = name
        self.expected = expected
        self.negate = negate
        self.location = here()

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        expected = None if self.expected is None else perform(self.expected, context)
        equal = context.configurations.get(self.name) == expected
        return "true" if equal != self.negate else "false"

    def describe(self) -> str:
        """How it was written."""
        what = "LaunchConfigurationNotEquals" if self.negate else "LaunchConfigurationEquals"
        expected = "None" if self.expected is None else describe(self.expected)
        return f"{what}({self.name!r}, {expected!r})"


class LaunchConfigurationEquals(_Wrapping):
    """``launch.conditions.LaunchConfigurationEquals`` (exact text; None: unset)."""

    NEGATE = False

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        expected = optional_value(expected_value)
        test = _ConfigurationEquals(launch_configuration_name, expected, self.NEGATE)
        super().__init__(LaunchkitCondition((test,), False, here()))

    def describe(self) -> str:
        """How it was written."""
        return describe(self.inner.value)


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """``launch.conditions.LaunchConfigurationNotEquals``."""

    NEGATE = True


def evaluate_condition_expression(context: Any, expression: Any) -> bool:
    """``launch.conditions.evaluate_condition_expression``: the substitutions' text as a
    condition (``true``/``1``, ``false``/``0``), an error for anything else."""
    return IfCondition(expression).evaluate(context)
