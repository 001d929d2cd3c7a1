"""The stand-in modules a ``*.launch.py`` imports: ``launch``, ``launch_ros``,
``ament_index_python``, ``lifecycle_msgs``, ``launch_xml`` and ``launch_yaml``, each with the
Jazzy names launchkit provides.

A name launchkit does not provide is an error naming it (``launch.actions.OpaqueCoroutine``)
and the line that asks for it, raised by the module's ``__getattr__``; the few known names
launchkit refuses on purpose say why.
"""

from __future__ import annotations

import types
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from launchkit.description.actions.base import Action
from launchkit.description.events import (
    Event,
    ExecutionComplete,
    ProcessExited,
    ProcessIO,
    ProcessStarted,
    Shutdown,
    ShutdownProcess,
    SignalProcess,
)
from launchkit.errors import LaunchFileError, PackageNotFoundError, RuntimeLaunchError
from launchkit.frontend.python import composition_api as C
from launchkit.frontend.python import conditions_api as K
from launchkit.frontend.python import event_api as E
from launchkit.frontend.python import launch_api as L
from launchkit.frontend.python import launch_substitutions as S
from launchkit.frontend.python import lifecycle_api as Y
from launchkit.frontend.python import process_api as P
from launchkit.frontend.python import ros_api as R
from launchkit.frontend.python import ros_params as RP
from launchkit.frontend.python import type_utils_api as T
from launchkit.frontend.python import utilities_api as U
from launchkit.frontend.python.description_sources import source_modules
from launchkit.frontend.python.values import LaunchContextView, SubstitutionLike, here, unsupported
from launchkit.packages import PackageIndex


def _module(name: str, **members: object) -> types.ModuleType:
    """A module whose missing names are errors naming them and the line asking."""
    module = types.ModuleType(name)
    module.__dict__.update(members)
    return _refusing(module)


def _refusing(module: types.ModuleType) -> types.ModuleType:
    """``module``, its missing names made errors naming them and the line asking."""
    name = module.__name__

    def missing(attribute: str) -> Any:
        if attribute.startswith("__"):
            raise AttributeError(attribute)
        raise LaunchFileError(
            f"{name}.{attribute} is not provided by launchkit",
            here(),
            expected=f"a name of {name} listed in docs/launch-files.md",
        )

    module.__getattr__ = missing  # type: ignore[method-assign]
    return module


#: ``launch.SomeSubstitutionsType_types_tuple``: what ``ensure_argument_type`` accepts as
#: substitutions.
SOME_SUBSTITUTIONS = (str, SubstitutionLike, Iterable)
#: The functions of ``launch.utilities.type_utils``.
_TYPE_UTILS = (
    "AllowedTypesTuple",
    "ListTypesTuple",
    "ScalarTypesTuple",
    "coerce_list",
    "coerce_to_type",
    "extract_type",
    "get_typed_value",
    "is_instance_of",
    "is_instance_of_valid_type",
    "is_normalized_substitution",
    "is_substitution",
    "is_typing_list",
    "is_valid_scalar_type",
    "normalize_typed_substitution",
    "perform_typed_substitution",
)


def _launch_modules() -> list[types.ModuleType]:
    actions = _module(
        "launch.actions",
        AppendEnvironmentVariable=L.AppendEnvironmentVariable,
        DeclareLaunchArgument=L.DeclareLaunchArgument,
        EmitEvent=E.EmitEvent,
        ExecuteLocal=P.ExecuteLocal,
        ExecuteProcess=P.ExecuteProcess,
        GroupAction=L.GroupAction,
        IncludeLaunchDescription=L.IncludeLaunchDescription,
        LogInfo=L.LogInfo,
        OpaqueCoroutine=unsupported("OpaqueCoroutine", "launchkit runs no asyncio loop"),
        OpaqueFunction=E.OpaqueFunction,
        PopEnvironment=L.PopEnvironment,
        PopLaunchConfigurations=L.PopLaunchConfigurations,
        PushEnvironment=L.PushEnvironment,
        PushLaunchConfigurations=L.PushLaunchConfigurations,
        RegisterEventHandler=E.RegisterEventHandler,
        ResetEnvironment=L.ResetEnvironment,
        ResetLaunchConfigurations=L.ResetLaunchConfigurations,
        SetEnvironmentVariable=L.SetEnvironmentVariable,
        SetLaunchConfiguration=L.SetLaunchConfiguration,
        Shutdown=L.Shutdown,
        TimerAction=L.TimerAction,
        UnregisterEventHandler=E.UnregisterEventHandler,
        UnsetEnvironmentVariable=L.UnsetEnvironmentVariable,
        UnsetLaunchConfiguration=L.UnsetLaunchConfiguration,
    )
    substitutions = _module(
        "launch.substitutions",
        AllSubstitution=S.AllSubstitution,
        AndSubstitution=S.AndSubstitution,
        AnonName=S.AnonName,
        AnySubstitution=S.AnySubstitution,
        Command=S.Command_,
        EnvironmentVariable=S.EnvironmentVariable,
        EqualsSubstitution=S.EqualsSubstitution,
        FileContent=S.FileContent,
        FindExecutable=S.FindExecutable,
        IfElseSubstitution=S.IfElseSubstitution,
        LaunchConfiguration=S.LaunchConfiguration,
        LaunchLogDir=S.LaunchLogDir,
        LocalSubstitution=S.LocalSubstitution,
        NotEqualsSubstitution=S.NotEqualsSubstitution,
        NotSubstitution=S.NotSubstitution,
        OrSubstitution=S.OrSubstitution,
        PathJoinSubstitution=S.PathJoinSubstitution,
        PythonExpression=S.PythonExpression,
        SubstitutionFailure=S.SubstitutionFailure,
        TextSubstitution=S.TextSubstitution,
        ThisLaunchFile=S.ThisLaunchFile,
        ThisLaunchFileDir=S.ThisLaunchFileDir,
    )
    conditions = _module(
        "launch.conditions",
        IfCondition=K.IfCondition,
        UnlessCondition=K.UnlessCondition,
        LaunchConfigurationEquals=K.LaunchConfigurationEquals,
        LaunchConfigurationNotEquals=K.LaunchConfigurationNotEquals,
        InvalidConditionExpressionError=RuntimeLaunchError,
        evaluate_condition_expression=K.evaluate_condition_expression,
    )
    frontend_sources = {n: _refusing(m) for n, m in source_modules().items()}
    sources = frontend_sources["launch.launch_description_sources"]
    handlers = _module(
        "launch.event_handlers",
        OnExecutionComplete=E.OnExecutionComplete,
        OnProcessExit=E.OnProcessExit,
        OnProcessIO=E.OnProcessIO,
        OnProcessStart=E.OnProcessStart,
        OnShutdown=E.OnShutdown,
        OnIncludeLaunchDescription=unsupported("OnIncludeLaunchDescription"),
    )
    process_events = _module(
        "launch.events.process",
        ProcessExited=ProcessExited,
        ProcessIO=ProcessIO,
        ProcessStarted=ProcessStarted,
        ShutdownProcess=ShutdownProcess,
        SignalProcess=SignalProcess,
        matches_executable=E.matches_executable,
        matches_name=E.matches_name,
        matches_pid=E.matches_pid,
    )
    events = _module(
        "launch.events",
        ExecutionComplete=ExecutionComplete,
        Shutdown=Shutdown,
        matches_action=E.matches_action,
        process=process_events,
    )
    descriptions = _module("launch.descriptions", Executable=P.Executable)
    type_utils = _module(
        "launch.utilities.type_utils",
        **{name: getattr(T, name) for name in _TYPE_UTILS},
    )
    utilities = _module(
        "launch.utilities",
        ensure_argument_type=U.ensure_argument_type,
        is_a=U.is_a,
        is_a_subclass=U.is_a_subclass,
        isclassinstance=U.isclassinstance,
        normalize_to_list_of_entities=U.normalize_to_list_of_entities,
        normalize_to_list_of_substitutions=U.normalize_to_list_of_substitutions,
        perform_substitutions=U.perform_substitutions,
        type_utils=type_utils,
    )
    some_substitutions_type = _module(
        "launch.some_substitutions_type",
        SomeSubstitutionsType=Any,
        SomeSubstitutionsType_types_tuple=SOME_SUBSTITUTIONS,
    )
    launch = _module(
        "launch",
        Action=Action,
        Condition=K.Condition,
        Event=Event,
        EventHandler=E.GenericEventHandler,
        InvalidLaunchFileError=LaunchFileError,
        LaunchContext=LaunchContextView,
        LaunchDescription=L.LaunchDescription,
        LaunchDescriptionEntity=Action,
        LaunchDescriptionSource=L.LaunchDescriptionSource,
        LaunchService=unsupported("LaunchService", "launchkit run is the launch service"),
        SomeEntitiesType=Any,
        SomeEntitiesType_types_tuple=(Action, Iterable),
        SomeSubstitutionsType=Any,
        SomeSubstitutionsType_types_tuple=SOME_SUBSTITUTIONS,
        Substitution=SubstitutionLike,
        actions=actions,
        conditions=conditions,
        descriptions=descriptions,
        event_handlers=handlers,
        events=events,
        launch_description_sources=sources,
        some_substitutions_type=some_substitutions_type,
        substitutions=substitutions,
        utilities=utilities,
    )
    return [
        *frontend_sources.values(),
        launch,
        actions,
        substitutions,
        conditions,
        handlers,
        events,
        process_events,
        descriptions,
        utilities,
        type_utils,
        some_substitutions_type,
    ]


def _ros_modules() -> list[types.ModuleType]:
    ros_actions = _module(
        "launch_ros.actions",
        ComposableNodeContainer=C.ComposableNodeContainer,
        LifecycleNode=Y.LifecycleNode,
        LifecycleTransition=Y.LifecycleTransition,
        LoadComposableNodes=C.LoadComposableNodes,
        Node=R.Node,
        PushROSNamespace=R.PushRosNamespace,
        PushRosNamespace=R.PushRosNamespace,
        ROSTimer=unsupported("ROSTimer", "timers on ROS time are not supported; use TimerAction"),
        RosTimer=unsupported("RosTimer", "timers on ROS time are not supported; use TimerAction"),
        SetParameter=R.SetParameter,
        SetParametersFromFile=R.SetParametersFromFile,
        SetRemap=R.SetRemap,
        SetROSLogDir=R.SetROSLogDir,
        SetUseSimTime=R.SetUseSimTime,
    )
    ros_substitutions = _module(
        "launch_ros.substitutions",
        ExecutableInPackage=R.ExecutableInPackage,
        FindPackage=R.FindPackage,
        FindPackagePrefix=R.FindPackagePrefix,
        FindPackageShare=R.FindPackageShare,
        Parameter=R.ParameterSubstitution,
    )
    parameters = dict(
        Parameter=RP.Parameter, ParameterFile=RP.ParameterFile, ParameterValue=RP.ParameterValue
    )
    parameter_descriptions = _module("launch_ros.parameter_descriptions", **parameters)
    descriptions = _module("launch_ros.descriptions", ComposableNode=C.ComposableNode, **parameters)
    lifecycle_events = _module(
        "launch_ros.events.lifecycle",
        ChangeState=Y.ChangeStateEvent,
        StateTransition=Y.StateTransition,
    )
    ros_events = _module(
        "launch_ros.events", lifecycle=lifecycle_events, matches_node_name=Y.matches_node_name
    )
    ros_handlers = _module("launch_ros.event_handlers", OnStateTransition=Y.OnStateTransition)
    launch_ros = _module(
        "launch_ros",
        actions=ros_actions,
        descriptions=descriptions,
        event_handlers=ros_handlers,
        events=ros_events,
        parameter_descriptions=parameter_descriptions,
        substitutions=ros_substitutions,
    )
    lifecycle_msg = _module("lifecycle_msgs.msg", State=Y.State, Transition=Y.Transition)
    lifecycle_msgs = _module("lifecycle_msgs", msg=lifecycle_msg)
    return [
        launch_ros,
        ros_actions,
        ros_substitutions,
        parameter_descriptions,
        descriptions,
        ros_events,
        lifecycle_events,
        ros_handlers,
        lifecycle_msgs,
        lifecycle_msg,
    ]


def _ament_modules() -> list[types.ModuleType]:
    index = PackageIndex()  # one per load: entry points are read once

    def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
        return str(L.find_package(index, package_name).share)

    def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
        return L.find_package(index, package_name).share

    def get_package_prefix(package_name: str) -> str:
        return str(L.find_package(index, package_name).prefix)

    def get_packages_with_prefixes() -> dict[str, str]:
        return {name: str(index.find(name).prefix) for name in index.names()}

    functions = dict(
        get_package_share_directory=get_package_share_directory,
        get_package_share_path=get_package_share_path,
        get_package_prefix=get_package_prefix,
        get_packages_with_prefixes=get_packages_with_prefixes,
        PackageNotFoundError=PackageNotFoundError,
    )
    packages = _module("ament_index_python.packages", **functions)
    ament = _module("ament_index_python", packages=packages, **functions)
    return [ament, packages]


def stand_in_modules() -> dict[str, types.ModuleType]:
    """Every stand-in module by its import name (a fresh set per launch file load)."""
    return {m.__name__: m for m in _launch_modules() + _ros_modules() + _ament_modules()}
