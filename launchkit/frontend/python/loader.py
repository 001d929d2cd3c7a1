"""Run a ``*.launch.py`` file's ``generate_launch_description()`` against the stand-in modules."""

from __future__ import annotations

import runpy
import sys
import types
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from launchkit.description.actions.base import Action
from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, LaunchkitError, Location
from launchkit.frontend.python import launch_api as L
from launchkit.frontend.python import launch_substitutions as S
from launchkit.frontend.python import ros_api as R
from launchkit.frontend.python import values
from launchkit.frontend.python.description_sources import source_modules
from launchkit.frontend.python.values import unsupported
from launchkit.packages import PackageIndex


def _module(name: str, **members: object) -> types.ModuleType:
    module = types.ModuleType(name)
    module.__dict__.update(members)
    return module


def _stand_in_modules() -> dict[str, types.ModuleType]:
    """The ``launch``, ``launch_ros`` and ``ament_index_python`` modules a launch file imports."""
    actions = _module(
        "launch.actions",
        DeclareLaunchArgument=L.DeclareLaunchArgument,
        IncludeLaunchDescription=L.IncludeLaunchDescription,
        ExecuteProcess=L.ExecuteProcess,
        GroupAction=L.GroupAction,
        LogInfo=L.LogInfo,
        TimerAction=L.TimerAction,
        SetLaunchConfiguration=L.SetLaunchConfiguration,
        SetEnvironmentVariable=L.SetEnvironmentVariable,
        UnsetEnvironmentVariable=L.UnsetEnvironmentVariable,
        AppendEnvironmentVariable=L.AppendEnvironmentVariable,
        Shutdown=L.Shutdown,
        OpaqueFunction=unsupported("OpaqueFunction"),
        RegisterEventHandler=unsupported("RegisterEventHandler"),
        EmitEvent=unsupported("EmitEvent"),
    )
    substitutions = _module(
        "launch.substitutions",
        LaunchConfiguration=S.LaunchConfiguration,
        EnvironmentVariable=S.EnvironmentVariable,
        TextSubstitution=S.TextSubstitution,
        PythonExpression=S.PythonExpression,
        PathJoinSubstitution=S.PathJoinSubstitution,
        Command=S.Command_,
        FindExecutable=S.FindExecutable,
        ThisLaunchFileDir=S.ThisLaunchFileDir,
        ThisLaunchFile=S.ThisLaunchFile,
        AnonName=S.AnonName,
        NotSubstitution=S.NotSubstitution,
        AndSubstitution=S.AndSubstitution,
        OrSubstitution=S.OrSubstitution,
        AnySubstitution=S.AnySubstitution,
        EqualsSubstitution=S.EqualsSubstitution,
    )
    conditions = _module(
        "launch.conditions",
        IfCondition=S.IfCondition,
        UnlessCondition=S.UnlessCondition,
        LaunchConfigurationEquals=S.LaunchConfigurationEquals,
        LaunchConfigurationNotEquals=S.LaunchConfigurationNotEquals,
    )
    frontend_sources = source_modules()
    sources = frontend_sources["launch.launch_description_sources"]
    launch = _module(
        "launch",
        LaunchDescription=L.LaunchDescription,
        actions=actions,
        substitutions=substitutions,
        conditions=conditions,
        launch_description_sources=sources,
    )
    ros_actions = _module(
        "launch_ros.actions",
        Node=R.Node,
        PushRosNamespace=R.PushRosNamespace,
        PushROSNamespace=R.PushRosNamespace,
        SetParameter=R.SetParameter,
        SetRemap=R.SetRemap,
        SetUseSimTime=R.SetUseSimTime,
        ComposableNodeContainer=unsupported("ComposableNodeContainer"),
        LifecycleNode=unsupported("LifecycleNode"),
    )
    ros_substitutions = _module(
        "launch_ros.substitutions",
        FindPackageShare=R.FindPackageShare,
        FindPackagePrefix=R.FindPackagePrefix,
        ExecutableInPackage=R.ExecutableInPackage,
    )
    launch_ros = _module("launch_ros", actions=ros_actions, substitutions=ros_substitutions)

    index = PackageIndex()  # one per load: entry points are read once

    def get_package_share_directory(package_name: str) -> str:
        return str(L.find_package(index, package_name).share)

    def get_package_prefix(package_name: str) -> str:
        return str(L.find_package(index, package_name).prefix)

    packages = _module(
        "ament_index_python.packages",
        get_package_share_directory=get_package_share_directory,
        get_package_prefix=get_package_prefix,
    )
    ament = _module("ament_index_python", packages=packages, **packages.__dict__)
    return {
        **frontend_sources,
        **{
            m.__name__: m
            for m in (
                launch,
                actions,
                substitutions,
                conditions,
                launch_ros,
                ros_actions,
                ros_substitutions,
                ament,
                packages,
            )
        },
    }


@contextmanager
def _stand_ins(path: Path) -> Iterator[None]:
    """Install the stand-in modules (hiding any real ``launch``) while ``path`` loads."""
    modules = _stand_in_modules()
    saved = {name: sys.modules.get(name) for name in modules}
    sys.modules.update(modules)
    values._loading.append(path)
    try:
        yield
    finally:
        values._loading.pop()
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module


def load_python_launch(path: Path, included_from: Location | None = None) -> LaunchDescription:
    """The description ``path``'s ``generate_launch_description()`` returns."""
    where = Location(str(path))
    with _stand_ins(path):
        try:
            namespace = runpy.run_path(str(path), run_name="__launch__")
            generate = namespace.get("generate_launch_description")
            if not callable(generate):
                raise LaunchFileError(
                    f"'{path.name}' has no generate_launch_description()",
                    where,
                    expected="a Python launch file defining generate_launch_description()",
                )
            result = generate()
        except LaunchkitError:
            raise
        except ImportError as error:
            raise LaunchFileError(
                f"'{path.name}' imports {error.name or error}, which launchkit does not provide",
                _error_location(error, path),
                expected="imports from launch, launch_ros and ament_index_python only",
            ) from None
        except Exception as error:
            raise LaunchFileError(
                f"'{path.name}' failed while building its launch description: "
                f"{type(error).__name__}: {error}",
                _error_location(error, path),
            ) from None
    if not isinstance(result, L.LaunchDescription):
        raise LaunchFileError(
            "generate_launch_description() did not return a LaunchDescription",
            where,
            expected="return LaunchDescription([...])",
        )
    actions: list[Action] = []
    for entity in result.entities:
        if not isinstance(entity, Action):
            raise LaunchFileError(
                f"'{type(entity).__name__}' in the LaunchDescription is not an action",
                where,
                expected="launch actions (DeclareLaunchArgument, Node, ExecuteProcess, ...)",
            )
        actions.append(entity)
    return LaunchDescription(path, actions, None)


def _error_location(error: BaseException, path: Path) -> Location:
    """The deepest line of ``path`` in the error's traceback."""
    line = None
    trace = error.__traceback__
    while trace is not None:
        if trace.tb_frame.f_code.co_filename == str(path):
            line = trace.tb_lineno
        trace = trace.tb_next
    return Location(str(path), line) if line else Location(str(path))
