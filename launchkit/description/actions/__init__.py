"""Actions: one module per tag (or per small family of tags)."""

from __future__ import annotations

from launchkit.description.actions.arg import DeclareArgument
from launchkit.description.actions.base import Action
from launchkit.description.actions.environment import AppendEnv, ResetEnv, SetEnv, UnsetEnv
from launchkit.description.actions.executable import ExecuteProcess, ProcessOptions
from launchkit.description.actions.group import Group, Keep, Reset
from launchkit.description.actions.include import Include, IncludeArg
from launchkit.description.actions.let import SetConfiguration
from launchkit.description.actions.log import Log, Shutdown
from launchkit.description.actions.node import ExecuteNode, Remap
from launchkit.description.actions.parameters import ParamDict, ParamFile, ParamGroup, ParamValue
from launchkit.description.actions.ros_scope import (
    PushRosNamespace,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
    SetUseSimTime,
)
from launchkit.description.actions.timer import Timer

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
