"""Stand-ins for the actions of ROS 2's ``launch`` package that launch files construct (its
processes are in ``process_api.py``, its event system in ``event_api.py``, its conditions in
``conditions_api.py``, its substitutions in ``launch_substitutions.py``).

Each action class *is* the matching launchkit action (a thin subclass whose constructor takes
the ROS keyword arguments), so the loaded file needs no translation step afterwards.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from launchkit.description import actions as lk
from launchkit.description.actions.base import Action, NameAction
from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.errors import LaunchFileError, PackageNotFoundError
from launchkit.frontend.python.values import here, optional_value, to_value
from launchkit.packages import FoundPackage, PackageIndex

# -- the description ---------------------------------------------------------------------------


class LaunchDescription:
    """``launch.LaunchDescription``: the list of actions ``generate_launch_description`` returns
    (also an entity an OpaqueFunction may return, or include)."""

    def __init__(self, initial_entities: Iterable[Any] | None = None, **_: Any) -> None:
        self.entities: list[Any] = list(initial_entities or [])

    def add_action(self, action: Action) -> None:
        """Append one action."""
        self.entities.append(action)

    add_entity = add_action


def flatten(entities: Any, what: str) -> list[Action]:
    """``entities`` (an action, a LaunchDescription, None, or a list of them) as actions."""
    if entities is None:
        return []
    if isinstance(entities, LaunchDescription):
        return flatten(entities.entities, what)
    if isinstance(entities, Action):
        return [entities]
    if isinstance(entities, Iterable) and not isinstance(entities, str):
        return [action for item in entities for action in flatten(item, what)]
    raise LaunchFileError(
        f"{what} gave a {type(entities).__name__}, not a launch action",
        here(),
        expected="launch actions (DeclareLaunchArgument, Node, ExecuteProcess, ...)",
    )


# -- actions -----------------------------------------------------------------------------------


class DeclareLaunchArgument(lk.DeclareArgument):
    """``launch.actions.DeclareLaunchArgument``."""

    def __init__(
        self,
        name: str,
        *,
        default_value: Any = None,
        description: str | None = None,
        choices: Iterable[str] | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(
            name,
            optional_value(default_value),
            description or "",
            tuple(choices or ()),
            here(),
            condition,
        )


class SetLaunchConfiguration(lk.SetConfiguration):
    """``launch.actions.SetLaunchConfiguration``."""

    def __init__(self, name: Any, value: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(name), to_value(value), here(), condition)


class UnsetLaunchConfiguration(NameAction):
    """``launch.actions.UnsetLaunchConfiguration``."""

    def __init__(self, name: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(name), here(), condition)

    def apply(self, context: LaunchContext, name: str) -> None:
        """Remove the configuration (no error when it is not set)."""
        context.configurations.pop(name, None)


class LaunchDescriptionSource:
    """``launch.launch_description_sources.*LaunchDescriptionSource``: where a file is, and how
    to read it (``syntax``; the classes are in ``description_sources.py``)."""

    syntax: str | None = None

    def __init__(self, launch_description_source: Any, *_: Any, **__: Any) -> None:
        self.location = to_value(launch_description_source)


class IncludeLaunchDescription(lk.Include):
    """``launch.actions.IncludeLaunchDescription``."""

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource | str,
        *,
        launch_arguments: Mapping[str, Any] | Iterable[tuple[str, Any]] | None = None,
        condition: Condition | None = None,
    ) -> None:
        source = (
            launch_description_source.location
            if isinstance(launch_description_source, LaunchDescriptionSource)
            else to_value(launch_description_source)
        )
        pairs = (
            launch_arguments.items()
            if isinstance(launch_arguments, Mapping)
            else (launch_arguments or [])
        )
        args = [lk.IncludeArg(str(name), to_value(value)) for name, value in pairs]
        super().__init__(
            source,
            args,
            here(),
            condition,
            syntax=getattr(launch_description_source, "syntax", None),
        )


class GroupAction(lk.Group):
    """``launch.actions.GroupAction``: ``launch_configurations`` are set inside the group
    (the only ones there when ``forwarding=False``)."""

    def __init__(
        self,
        actions: Iterable[Action],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: Mapping[Any, Any] | None = None,
        condition: Condition | None = None,
    ) -> None:
        pairs = [(to_value(k), to_value(v)) for k, v in (launch_configurations or {}).items()]
        location = here()
        children = list(actions)
        keeps: list[lk.Keep] = []
        if scoped and not forwarding:
            keeps = [lk.Keep(name, value) for name, value in pairs]
        else:
            sets = [lk.SetConfiguration(name, value, location) for name, value in pairs]
            children = [*sets, *children]
        super().__init__(children, scoped, forwarding, keeps, location, condition)


class ResetLaunchConfigurations(lk.Reset):
    """``launch.actions.ResetLaunchConfigurations``."""

    def __init__(
        self,
        launch_configurations: Mapping[Any, Any] | None = None,
        *,
        condition: Condition | None = None,
    ) -> None:
        keeps = [
            lk.Keep(to_value(k), to_value(v)) for k, v in (launch_configurations or {}).items()
        ]
        super().__init__(keeps, here(), condition)


class _Push(Action):
    """Push (``pop=False``) or pop the configurations or the environment of the scope."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        super().__init__(here(), condition)


class PushLaunchConfigurations(_Push):
    """``launch.actions.PushLaunchConfigurations``: save the scope (configurations and ROS
    globals); the matching Pop restores it."""

    def execute(self, context: LaunchContext) -> None:
        """Save a copy."""
        context.saved_scopes.append(context.scope.copy())


class PopLaunchConfigurations(_Push):
    """``launch.actions.PopLaunchConfigurations``: back to the last pushed configurations
    (the environment stays as it is)."""

    def execute(self, context: LaunchContext) -> None:
        """Restore."""
        if context.saved_scopes:
            saved = context.saved_scopes.pop()
            saved.environment = context.scope.environment
            context.scope = saved


class PushEnvironment(_Push):
    """``launch.actions.PushEnvironment``."""

    def execute(self, context: LaunchContext) -> None:
        """Save a copy of the environment."""
        context.saved_environments.append(dict(context.environment))


class PopEnvironment(_Push):
    """``launch.actions.PopEnvironment``."""

    def execute(self, context: LaunchContext) -> None:
        """Restore the last pushed environment."""
        if context.saved_environments:
            context.environment.clear()
            context.environment.update(context.saved_environments.pop())


class ResetEnvironment(lk.ResetEnv):
    """``launch.actions.ResetEnvironment``."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        super().__init__(here(), condition)


class LogInfo(lk.Log):
    """``launch.actions.LogInfo``."""

    def __init__(self, *, msg: Any, condition: Condition | None = None) -> None:
        super().__init__(to_value(msg), "INFO", here(), condition)


class TimerAction(lk.Timer):
    """``launch.actions.TimerAction``."""

    def __init__(
        self,
        *,
        period: Any,
        actions: Iterable[Action],
        cancel_on_shutdown: bool = True,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(to_value(period), list(actions), cancel_on_shutdown, here(), condition)


class SetEnvironmentVariable(lk.SetEnv):
    """``launch.actions.SetEnvironmentVariable``."""

    def __init__(self, name: Any, value: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(name), to_value(value), here(), condition)


class UnsetEnvironmentVariable(lk.UnsetEnv):
    """``launch.actions.UnsetEnvironmentVariable``."""

    def __init__(self, name: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(name), here(), condition)


class AppendEnvironmentVariable(lk.AppendEnv):
    """``launch.actions.AppendEnvironmentVariable``."""

    def __init__(
        self,
        name: Any,
        value: Any,
        *,
        prepend: bool = False,
        separator: Any = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(
            to_value(name), to_value(value), prepend, optional_value(separator), here(), condition
        )


class Shutdown(lk.Shutdown):
    """``launch.actions.Shutdown``."""

    def __init__(self, *, reason: Any = None, condition: Condition | None = None) -> None:
        super().__init__(to_value(reason), here(), condition)


def find_package(index: PackageIndex, name: str) -> FoundPackage:
    """``ament_index_python``'s lookups through launchkit's package index; an unknown package is
    an error at the launch file's line."""
    try:
        return index.find(name)
    except PackageNotFoundError as error:
        location = here()
        if error.location is None and location is not None:
            raise error.with_location(location) from None
        raise
