"""Stand-ins for the conditions and substitutions of ROS 2's ``launch`` package.

Each substitution class wraps the matching launchkit substitution; each condition is a launchkit
:class:`Condition`. Locations are the lines of the launch file that built them.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions import And as AndSub
from launchkit.description.substitutions import Anon as AnonSub
from launchkit.description.substitutions import (
    AnyOf,
    Command,
    Dirname,
    Env,
    Equals,
    Eval,
    Filename,
    FindExec,
    Not,
    NotEquals,
    Text,
    Var,
)
from launchkit.description.substitutions import Or as OrSub
from launchkit.description.substitutions.base import Substitution, perform
from launchkit.frontend.python.values import SubstitutionLike, here, to_value

# -- conditions --------------------------------------------------------------------------------


def _condition(value: Any, negate: bool) -> Condition:
    return Condition(to_value(value), negate, here())


def IfCondition(predicate_expression: Any) -> Condition:
    """``launch.conditions.IfCondition``."""
    return _condition(predicate_expression, False)


def UnlessCondition(predicate_expression: Any) -> Condition:
    """``launch.conditions.UnlessCondition``."""
    return _condition(predicate_expression, True)


def LaunchConfigurationEquals(name: str, expected_value: Any) -> Condition:
    """``launch.conditions.LaunchConfigurationEquals``."""
    test = Equals([(Var([to_value(name)]),), to_value(expected_value)])
    return Condition((test,), False, here())


def LaunchConfigurationNotEquals(name: str, expected_value: Any) -> Condition:
    """``launch.conditions.LaunchConfigurationNotEquals``."""
    test = NotEquals([(Var([to_value(name)]),), to_value(expected_value)])
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
    """``launch.substitutions.PathJoinSubstitution``."""

    def __init__(self, substitutions: Iterable[Any]) -> None:
        parts: list[Any] = []
        for index, item in enumerate(substitutions):
            if index:
                parts.append("/")
            parts.append(item)
        super().__init__(_Joined(to_value(parts)))


class _Joined(Substitution):
    """A concatenation behaving as one substitution (what PathJoinSubstitution yields)."""

    def __init__(self, value: tuple[Any, ...]) -> None:
        self.value = value

    def perform(self, context: LaunchContext) -> str:
        """The parts performed and joined."""
        return perform(self.value, context)

    def describe(self) -> str:
        """The parts, described."""
        return "".join(part.describe() for part in self.value)


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


class EqualsSubstitution(SubstitutionLike):
    """``launch.substitutions.EqualsSubstitution``."""

    def __init__(self, left: Any, right: Any) -> None:
        super().__init__(Equals([to_value(left), to_value(right)], here()))
