"""Stand-ins for the conditions and substitutions of ROS 2's ``launch`` package.

Each substitution class wraps the matching launchkit substitution; each condition is a launchkit
:class:`Condition`. Locations are the lines of the launch file that built them.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions import (
    AllOf,
    AnyOf,
    Command,
    Dirname,
    Env,
    Equals,
    Eval,
    Filename,
    FindExec,
    IfElse,
    LogDir,
    Not,
    NotEquals,
    Text,
    Var,
)
from launchkit.description.substitutions import And as AndSub
from launchkit.description.substitutions import Anon as AnonSub
from launchkit.description.substitutions import FileContent as FileContentSub
from launchkit.description.substitutions import Or as OrSub
from launchkit.description.substitutions.base import Substitution, Value, describe, perform
from launchkit.description.substitutions.local import Local
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.python.context_view import LaunchContextView
from launchkit.frontend.python.values import (
    SubstitutionLike,
    call_user,
    current_modules,
    here,
    optional_value,
    to_value,
)

# -- conditions --------------------------------------------------------------------------------


def _condition(value: Any, negate: bool) -> Condition:
    return Condition(to_value(value), negate, here())


def IfCondition(predicate_expression: Any) -> Condition:
    """``launch.conditions.IfCondition``."""
    return _condition(predicate_expression, False)


def UnlessCondition(predicate_expression: Any) -> Condition:
    """``launch.conditions.UnlessCondition``."""
    return _condition(predicate_expression, True)


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


def LaunchConfigurationEquals(launch_configuration_name: str, expected_value: Any) -> Condition:
    """``launch.conditions.LaunchConfigurationEquals`` (exact text; None: unset)."""
    test = _ConfigurationEquals(launch_configuration_name, optional_value(expected_value), False)
    return Condition((test,), False, here())


def LaunchConfigurationNotEquals(launch_configuration_name: str, expected_value: Any) -> Condition:
    """``launch.conditions.LaunchConfigurationNotEquals``."""
    test = _ConfigurationEquals(launch_configuration_name, optional_value(expected_value), True)
    return Condition((test,), False, here())


# -- substitutions -----------------------------------------------------------------------------


class LaunchConfiguration(SubstitutionLike):
    """``launch.substitutions.LaunchConfiguration``."""

    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        args = [to_value(variable_name)] + ([to_value(default)] if default is not None else [])
        super().__init__(Var(args, here()))


class EnvironmentVariable(SubstitutionLike):
    """``launch.substitutions.EnvironmentVariable``."""

    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        args = [to_value(name)] + ([to_value(default_value)] if default_value is not None else [])
        super().__init__(Env(args, here()))


class TextSubstitution(SubstitutionLike):
    """``launch.substitutions.TextSubstitution``."""

    def __init__(self, *, text: str) -> None:
        super().__init__(Text(text))
        self.text = text


class LocalSubstitution(SubstitutionLike):
    """``launch.substitutions.LocalSubstitution('event.reason')``: a local of the context (the
    event, in a handler's actions), by attribute path."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        super().__init__(Local(expression, description, here()))


class FileContent(SubstitutionLike):
    """``launch.substitutions.FileContent``."""

    def __init__(self, path: Any) -> None:
        super().__init__(FileContentSub([to_value(path)], here()))


class LaunchLogDir(SubstitutionLike):
    """``launch.substitutions.LaunchLogDir``: this run's log directory."""

    def __init__(self) -> None:
        super().__init__(LogDir([], here()))


class IfElseSubstitution(SubstitutionLike):
    """``launch.substitutions.IfElseSubstitution``."""

    def __init__(self, condition: Any, if_value: Any = "", else_value: Any = "") -> None:
        if if_value == else_value == "":
            raise LaunchFileError(
                "IfElseSubstitution has neither if_value nor else_value",
                here(),
                expected="if_value=... or else_value=...",
            )
        args = [to_value(condition), to_value(if_value), to_value(else_value)]
        super().__init__(IfElse(args, here()))


class SubstitutionFailure(RuntimeError):
    """``launch.substitutions.SubstitutionFailure``: raise it from a function to fail."""


class Substitution_(SubstitutionLike):
    """``launch.Substitution``: base of a launch file's own substitution classes, which
    define ``perform(self, context)`` (and ``describe``)."""

    def __init__(self) -> None:
        super().__init__(_UserSubstitution(self, here()))

    def perform(self, context: Any) -> str:
        """Overridden by the subclass."""
        raise NotImplementedError(f"{type(self).__name__} does not define perform()")


class _UserSubstitution(Substitution):
    """Calls a launch file's own substitution's ``perform`` with the context view."""

    def __init__(self, owner: Substitution_, location: Location | None) -> None:
        self.owner = owner
        self.location = location
        self._modules = current_modules()

    def perform(self, context: LaunchContext) -> str:
        """What the user's ``perform`` returns."""
        what = f"{type(self.owner).__name__}.perform"
        result = call_user(self.owner.perform, what, self._modules, LaunchContextView(context))
        return str(result)

    def describe(self) -> str:
        """The class name."""
        return f"{type(self.owner).__name__}()"


class PythonExpression(SubstitutionLike):
    """``launch.substitutions.PythonExpression``: evaluated by ``$(eval)``'s sandbox, with
    ``python_modules`` (each a name or a substitution; ``math`` is the only one offered)."""

    def __init__(self, expression: Any, python_modules: Any = ("math",)) -> None:
        names = [python_modules] if isinstance(python_modules, str | SubstitutionLike) else None
        modules: list[Any] = []
        for index, name in enumerate(names or python_modules):
            modules += [",", name] if index else [name]
        super().__init__(Eval([to_value(expression), to_value(modules)], here()))


class PathJoinSubstitution(SubstitutionLike):
    """``launch.substitutions.PathJoinSubstitution``: the parts joined as ``os.path.join``
    does (an absolute part starts the path over). A part may itself be a list, concatenated
    first (as later ROS releases allow; Jazzy refuses it)."""

    def __init__(self, substitutions: Iterable[Any]) -> None:
        items = [substitutions] if isinstance(substitutions, str) else list(substitutions)
        super().__init__(_PathJoin([to_value(item) for item in items], here()))


class _PathJoin(Substitution):
    """The parts performed, then joined with ``os.path.join``."""

    def __init__(self, parts: list[Value], location: Location | None) -> None:
        self.parts = parts
        self.location = location

    def perform(self, context: LaunchContext) -> str:
        """The joined path."""
        texts = [perform(part, context) for part in self.parts]
        return os.path.join(*texts) if texts else ""

    def describe(self) -> str:
        """``PathJoin('a' + 'b')`` as ROS describes it."""
        return "PathJoin(" + " + ".join(describe(part) for part in self.parts) + ")"


class Command_(SubstitutionLike):
    """``launch.substitutions.Command``: its parts are concatenated into one command line (as
    in ROS, ``Command(['xacro ', path])``), which is then split like a shell would."""

    def __init__(self, command: Any, *, on_stderr: str = "fail") -> None:
        super().__init__(Command([to_value(command), to_value(on_stderr)], here()))


class FindExecutable(SubstitutionLike):
    """``launch.substitutions.FindExecutable``."""

    def __init__(self, *, name: Any) -> None:
        super().__init__(FindExec([to_value(name)], here()))


class ThisLaunchFileDir(SubstitutionLike):
    """``launch.substitutions.ThisLaunchFileDir``."""

    def __init__(self) -> None:
        super().__init__(Dirname([], here()))


class ThisLaunchFile(SubstitutionLike):
    """``launch.substitutions.ThisLaunchFile``."""

    def __init__(self) -> None:
        super().__init__(Filename([], here()))


class AnonName(SubstitutionLike):
    """``launch.substitutions.AnonName``."""

    def __init__(self, name: Any) -> None:
        super().__init__(AnonSub([to_value(name)], here()))


class NotSubstitution(SubstitutionLike):
    """``launch.substitutions.NotSubstitution``."""

    def __init__(self, value: Any) -> None:
        super().__init__(Not([to_value(value)], here()))


class AndSubstitution(SubstitutionLike):
    """``launch.substitutions.AndSubstitution``."""

    def __init__(self, left: Any, right: Any) -> None:
        super().__init__(AndSub([to_value(left), to_value(right)], here()))


class OrSubstitution(SubstitutionLike):
    """``launch.substitutions.OrSubstitution``."""

    def __init__(self, left: Any, right: Any) -> None:
        super().__init__(OrSub([to_value(left), to_value(right)], here()))


class AnySubstitution(SubstitutionLike):
    """``launch.substitutions.AnySubstitution``."""

    def __init__(self, *args: Any) -> None:
        super().__init__(AnyOf([to_value(a) for a in args], here()))


class AllSubstitution(SubstitutionLike):
    """``launch.substitutions.AllSubstitution``."""

    def __init__(self, *args: Any) -> None:
        super().__init__(AllOf([to_value(a) for a in args], here()))


class EqualsSubstitution(SubstitutionLike):
    """``launch.substitutions.EqualsSubstitution`` (as booleans, then numbers, then text)."""

    def __init__(self, left: Any, right: Any) -> None:
        super().__init__(Equals([to_value(left), to_value(right)], here()))


class NotEqualsSubstitution(SubstitutionLike):
    """``launch.substitutions.NotEqualsSubstitution``."""

    def __init__(self, left: Any, right: Any) -> None:
        super().__init__(NotEquals([to_value(left), to_value(right)], here()))
