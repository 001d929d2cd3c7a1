"""Stand-ins for ``launch_ros`` actions and substitutions that launch files construct
(parameters are in ``ros_params.py``, lifecycle and composable nodes in their own modules)."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

import yaml

from launchkit.description import actions as lk
from launchkit.description.actions.base import Action
from launchkit.description.actions.parameters import ParamDict, ParamEntry
from launchkit.description.conditions import Condition
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions import ExecInPkg, FindPkgPrefix, FindPkgShare, Param
from launchkit.description.substitutions.base import perform
from launchkit.errors import LaunchFileError
from launchkit.frontend.python.launch_api import find_package
from launchkit.frontend.python.process_api import process_options, words_of
from launchkit.frontend.python.ros_params import parameter_entries
from launchkit.frontend.python.values import (
    SubstitutionLike,
    here,
    optional_value,
    to_value,
)
from launchkit.packages import PackageIndex


class FindPackage(SubstitutionLike):
    """``launch_ros.substitutions.FindPackage``: the base of the two below."""

    KIND: type[FindPkgShare] | type[FindPkgPrefix] = FindPkgShare

    def __init__(self, package: Any) -> None:
        super().__init__(self.KIND([to_value(package)], here()))

    def find(self, package_name: str) -> str:
        """The directory for ``package_name`` (as the substitution would give it); an unknown
        package is an error at the launch file's line."""
        found = find_package(PackageIndex(), package_name)
        return str(found.share if self.KIND is FindPkgShare else found.prefix)


class FindPackageShare(FindPackage):
    """``launch_ros.substitutions.FindPackageShare``."""

    KIND = FindPkgShare


class FindPackagePrefix(FindPackage):
    """``launch_ros.substitutions.FindPackagePrefix``."""

    KIND = FindPkgPrefix


class ExecutableInPackage(SubstitutionLike):
    """``launch_ros.substitutions.ExecutableInPackage``."""

    def __init__(self, executable: Any, package: Any) -> None:
        super().__init__(ExecInPkg([to_value(executable), to_value(package)], here()))


class ParameterSubstitution(SubstitutionLike):
    """``launch_ros.substitutions.Parameter``: a parameter set with SetParameter."""

    def __init__(self, name: Any, *, default: Any = None) -> None:
        args = [to_value(name)] + ([to_value(default)] if default is not None else [])
        super().__init__(Param(args, here()))


def flat_parameters(parameters: Iterable[Any] | None) -> list[ParamEntry]:
    """A Node's parameters list as launchkit's entries, in order (a dict stays together: it
    is one params file)."""
    return [
        ParamDict(item) if isinstance(item, list) else item  # type: ignore[arg-type]
        for item in parameter_entries(parameters or [])
    ]


def remap_rules(remappings: Iterable[Any] | None) -> list[lk.Remap]:
    """``remappings=[('from', 'to'), ...]``."""
    rules = []
    for rule in remappings or []:
        if isinstance(rule, str) or len(rule) != 2:
            raise LaunchFileError(
                f"remapping {rule!r} is not a pair",
                here(),
                expected="remappings=[('from', 'to'), ...]",
            )
        rules.append(lk.Remap(to_value(rule[0]), to_value(rule[1])))
    return rules


def node_arguments(
    *,
    executable: Any,
    package: Any = None,
    name: Any = None,
    namespace: Any = None,
    exec_name: Any = None,
    parameters: Iterable[Any] | None = None,
    remappings: Iterable[Any] | None = None,
    arguments: Iterable[Any] | None = None,
    ros_arguments: Iterable[Any] | None = None,
    condition: Condition | None = None,
    **options: Any,
) -> dict[str, Any]:
    """``Node(...)``'s keyword arguments as launchkit's ExecuteNode arguments."""
    return dict(
        pkg=optional_value(package),
        exec=to_value(executable),
        options=process_options(**options),
        node_name=optional_value(name),
        namespace=optional_value(namespace),
        exec_name=optional_value(exec_name),
        args=words_of(arguments) if arguments is not None else None,
        ros_args=words_of(ros_arguments) if ros_arguments is not None else None,
        params=flat_parameters(parameters),
        remaps=remap_rules(remappings),
        location=here(),
        condition=condition,
    )


class Node(lk.ExecuteNode):
    """``launch_ros.actions.Node``."""

    def __init__(self, **kwargs: Any) -> None:
        arguments = node_arguments(**kwargs)
        super().__init__(
            arguments.pop("pkg"), arguments.pop("exec"), arguments.pop("options"), **arguments
        )


class PushRosNamespace(lk.PushRosNamespace):
    """``launch_ros.actions.PushROSNamespace`` (also ``PushRosNamespace``)."""

    def __init__(self, namespace: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(namespace), here(), condition)


class SetParameter(lk.SetParameter):
    """``launch_ros.actions.SetParameter`` (a Python value keeps its type: ``True``, ``5``,
    ``[1, 2]``)."""

    def __init__(self, name: Any, value: Any, *, condition: Condition | None = None) -> None:
        if isinstance(value, bool | int | float) or (
            isinstance(value, list | tuple)
            and all(isinstance(v, bool | int | float) for v in value)
        ):
            value = (
                yaml.safe_dump(
                    list(value) if isinstance(value, tuple) else value, default_flow_style=True
                )
                .strip()
                .removesuffix("...")
                .strip()
            )
        super().__init__(to_value(name), to_value(value), here(), condition)


class SetParametersFromFile(lk.SetParametersFromFile):
    """``launch_ros.actions.SetParametersFromFile``."""

    def __init__(self, filename: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(filename), here(), condition)


class SetRemap(lk.SetRemap):
    """``launch_ros.actions.SetRemap``."""

    def __init__(self, src: Any, dst: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(src), to_value(dst), here(), condition)


class SetUseSimTime(lk.SetUseSimTime):
    """``launch_ros.actions.SetUseSimTime``: as in Jazzy, the launch's own ROS clock (for ROS
    timers), not a parameter of the nodes; launchkit checks the value."""

    def __init__(self, value: Any, *, condition: Condition | None = None) -> None:
        super().__init__(to_value(value), here(), condition, nodes=False)


class SetROSLogDir(Action):
    """``launch_ros.actions.SetROSLogDir``: ``ROS_LOG_DIR`` for the nodes started later in
    scope, relative to the current one (``$ROS_LOG_DIR``, else ``~/.ros/log``)."""

    def __init__(self, *, new_log_dir: Any, condition: Condition | None = None) -> None:
        super().__init__(here(), condition)
        self.new_log_dir = to_value(new_log_dir)

    def execute(self, context: LaunchContext) -> None:
        """Set it in the scope's environment."""
        current = context.environment.get("ROS_LOG_DIR") or os.path.expanduser("~/.ros/log")
        path = os.path.join(current, perform(self.new_log_dir, context))
        context.environment["ROS_LOG_DIR"] = path
