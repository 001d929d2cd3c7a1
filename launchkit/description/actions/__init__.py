"""Actions: one module per tag (or per small family of tags)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes

if TYPE_CHECKING:
    from launchkit.description.actions.arg import DeclareArgument
    from launchkit.description.actions.base import Action
    from launchkit.description.actions.environment import AppendEnv, ResetEnv, SetEnv, UnsetEnv
    from launchkit.description.actions.executable import ExecuteProcess, ProcessOptions
    from launchkit.description.actions.group import Group, Keep, Reset
    from launchkit.description.actions.include import Include, IncludeArg
    from launchkit.description.actions.let import SetConfiguration
    from launchkit.description.actions.log import Log, Shutdown
    from launchkit.description.actions.node import ExecuteNode, Remap
    from launchkit.description.actions.parameters import (
        ParamDict,
        ParamFile,
        ParamGroup,
        ParamValue,
    )
    from launchkit.description.actions.ros_scope import (
        PushRosNamespace,
        SetParameter,
        SetParametersFromFile,
        SetRemap,
        SetUseSimTime,
    )
    from launchkit.description.actions.timer import Timer

# Name -> its module, imported on first use (PEP 562): a launch imports only the actions its
# files use, not every action class with its dataclasses.
_WHERE = {
    "Action": "base",
    "DeclareArgument": "arg",
    "AppendEnv": "environment",
    "ResetEnv": "environment",
    "SetEnv": "environment",
    "UnsetEnv": "environment",
    "ExecuteProcess": "executable",
    "ProcessOptions": "executable",
    "Group": "group",
    "Keep": "group",
    "Reset": "group",
    "Include": "include",
    "IncludeArg": "include",
    "SetConfiguration": "let",
    "Log": "log",
    "Shutdown": "log",
    "ExecuteNode": "node",
    "Remap": "node",
    "ParamDict": "parameters",
    "ParamFile": "parameters",
    "ParamGroup": "parameters",
    "ParamValue": "parameters",
    "PushRosNamespace": "ros_scope",
    "SetParameter": "ros_scope",
    "SetParametersFromFile": "ros_scope",
    "SetRemap": "ros_scope",
    "SetUseSimTime": "ros_scope",
    "Timer": "timer",
}


__getattr__ = lazy_attributes(__name__, {n: f".{m}" for n, m in _WHERE.items()}, globals())


__all__ = [
    "Action",
    "AppendEnv",
    "DeclareArgument",
    "ExecuteNode",
    "ExecuteProcess",
    "Group",
    "Include",
    "IncludeArg",
    "Keep",
    "Log",
    "ParamDict",
    "ParamFile",
    "ParamGroup",
    "ParamValue",
    "ProcessOptions",
    "PushRosNamespace",
    "Remap",
    "Reset",
    "ResetEnv",
    "SetConfiguration",
    "SetEnv",
    "SetParameter",
    "SetParametersFromFile",
    "SetRemap",
    "SetUseSimTime",
    "Shutdown",
    "Timer",
    "UnsetEnv",
]
