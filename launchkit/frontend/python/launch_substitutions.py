"""Stand-ins for the substitutions of ROS 2's ``launch`` package (its conditions are in
``conditions_api.py``).

Each substitution class wraps the matching launchkit substitution. Locations are the lines of
the launch file that built them.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

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
from launchkit.frontend.python.values import (
    SubstitutionLike,
    here,
    to_value,
)

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
