"""Stand-ins for the actions of ROS 2's ``launch`` package that launch files construct (its
conditions and substitutions are in ``launch_substitutions.py``).

Each action class *is* the matching launchkit action (a thin subclass whose constructor takes
the ROS keyword arguments), so the loaded file needs no translation step afterwards.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from launchkit.description import actions as lk
from launchkit.description.actions.base import Action
from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.process_spec import ProcessSpec
from launchkit.description.substitutions.base import perform
from launchkit.errors import PackageNotFoundError
from launchkit.frontend.python.values import (
    argv_text,
    here,
    optional_value,
    to_value,
    unsupported,
)
from launchkit.packages import FoundPackage, PackageIndex

# -- the description ---------------------------------------------------------------------------


class LaunchDescription:
    """``launch.LaunchDescription``: the list of actions ``generate_launch_description`` returns."""

    def __init__(self, initial_entities: Iterable[Action] | None = None) -> None:
        self.entities: list[Action] = list(initial_entities or [])

    def add_action(self, action: Action) -> None:
        """Append one action."""
        self.entities.append(action)

    add_entity = add_action


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


class LaunchDescriptionSource:
    """``launch.launch_description_sources.*LaunchDescriptionSource``: where a file is, and how
    to read it (``syntax``; the classes are in ``description_sources.py``)."""

    syntax: str | None = None

    def __init__(self, launch_description_source: Any) -> None:
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


def process_options(
    *,
    cwd: Any = None,
    name: Any = None,
    prefix: Any = None,
    output: Any = None,
    shell: bool | None = None,
    emulate_tty: bool | None = None,
    sigterm_timeout: Any = None,
    sigkill_timeout: Any = None,
    respawn: Any = None,
    respawn_delay: Any = None,
    respawn_max_retries: Any = None,
    additional_env: Mapping[Any, Any] | None = None,
    env: Mapping[Any, Any] | None = None,
    on_exit: Any = None,
) -> lk.ProcessOptions:
    """The process keyword arguments ExecuteProcess and Node share, as ProcessOptions."""
    if isinstance(on_exit, lk.Shutdown) or (
        isinstance(on_exit, list) and len(on_exit) == 1 and isinstance(on_exit[0], lk.Shutdown)
    ):
        on_exit = "shutdown"  # on_exit=Shutdown() or [Shutdown()]: launchkit's on_exit="shutdown"
    elif on_exit is not None and not isinstance(on_exit, str):
        unsupported("on_exit with actions other than Shutdown()")()
    environment = [
        (to_value(k), to_value(v)) for k, v in {**(env or {}), **(additional_env or {})}.items()
    ]
    return lk.ProcessOptions(
        cwd=optional_value(cwd),
        name=optional_value(name),
        launch_prefix=optional_value(prefix),
        output=optional_value(output),
        shell=optional_value(shell),
        emulate_tty=optional_value(emulate_tty),
        sigterm_timeout=optional_value(sigterm_timeout),
        sigkill_timeout=optional_value(sigkill_timeout),
        respawn=optional_value(respawn),
        respawn_delay=optional_value(respawn_delay),
        respawn_max_retries=optional_value(respawn_max_retries),
        on_exit=optional_value(on_exit),
        env=environment,
    )


class ExecuteProcess(lk.ExecuteProcess):
    """``launch.actions.ExecuteProcess``: ``cmd`` is a list of words; empty words are dropped,
    as ROS does, so ``PythonExpression`` can switch a flag off by yielding ''."""

    def __init__(
        self, *, cmd: Iterable[Any], condition: Condition | None = None, **options: Any
    ) -> None:
        words = list(cmd)
        self.words = [to_value(word) for word in words]
        super().__init__(argv_text(words), process_options(**options), here(), condition)

    def evaluate(self, context: LaunchContext) -> ProcessSpec:
        """The process, its argv built word by word."""
        from launchkit.description.actions.executable import ProcessBuilder

        builder = ProcessBuilder(self.options, context, self.location)
        words = [w for w in (perform(word, context) for word in self.words) if w != ""]
        if builder.flag(self.options.shell, False, "shell"):
            text = " ".join(words)
            return builder.build(["/bin/sh", "-c", text], words[0] if words else "sh", False)
        return builder.build(words, words[0] if words else "", False)


class GroupAction(lk.Group):
    """``launch.actions.GroupAction``."""

    def __init__(
        self,
        actions: Iterable[Action],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: Mapping[Any, Any] | None = None,
        condition: Condition | None = None,
    ) -> None:
        keeps = [
            lk.Keep(to_value(k), to_value(v)) for k, v in (launch_configurations or {}).items()
        ]
        super().__init__(list(actions), scoped, forwarding, keeps, here(), condition)


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
