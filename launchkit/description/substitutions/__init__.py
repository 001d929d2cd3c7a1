"""Substitutions: one small class per ``$(...)`` kind, and the registry the parser uses."""

from __future__ import annotations

from launchkit.description.substitutions.base import Call, Substitution, Text, Value, perform
from launchkit.description.substitutions.command import Command
from launchkit.description.substitutions.configuration import Anon, Var
from launchkit.description.substitutions.environment import Env
from launchkit.description.substitutions.expression import Eval
from launchkit.description.substitutions.logic import (
    AllOf,
    And,
    AnyOf,
    Equals,
    IfElse,
    Not,
    NotEquals,
    Or,
)
from launchkit.description.substitutions.package import ExecInPkg, FindPkgPrefix, FindPkgShare
from launchkit.description.substitutions.parameter import Param
from launchkit.description.substitutions.paths import (
    Dirname,
    FileContent,
    Filename,
    FindExec,
    LaunchLogDir,
    LogDir,
)

#: ``$(name ...)`` -> class; the tokenizer rejects any other name.
SUBSTITUTIONS: dict[str, type[Call]] = {
    kind.NAME: kind
    for kind in (
        Var,
        Env,
        Eval,
        Command,
        FindExec,
        FindPkgShare,
        FindPkgPrefix,
        ExecInPkg,
        Dirname,
        Filename,
        Anon,
        Not,
        And,
        Or,
        AnyOf,
        AllOf,
        Equals,
        NotEquals,
        IfElse,
        FileContent,
        LogDir,
        LaunchLogDir,
        Param,
    )
}

__all__ = [
    "SUBSTITUTIONS",
    "AllOf",
    "And",
    "Anon",
    "AnyOf",
    "Call",
    "Command",
    "Dirname",
    "Env",
    "Equals",
    "Eval",
    "ExecInPkg",
    "FileContent",
    "Filename",
    "FindExec",
    "FindPkgPrefix",
    "FindPkgShare",
    "IfElse",
    "LaunchLogDir",
    "LogDir",
    "Not",
    "NotEquals",
    "Or",
    "Param",
    "Substitution",
    "Text",
    "Value",
    "Var",
    "perform",
]
