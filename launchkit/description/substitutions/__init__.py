"""Substitutions: one small class per ``$(...)`` kind, and the registry the parser uses.

Each class is imported when first used (PEP 562, and :data:`SUBSTITUTIONS` imports a kind's
module when the parser first meets it): a launch file without ``$(command)`` does not import
``subprocess`` for it.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes
from launchkit.description.substitutions.base import Call, Substitution, Text, Value, perform

if TYPE_CHECKING:
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

# ``$(name ...)`` -> (module, class); tests/engine/test_substitutions*.py check it against
# each class's ``NAME``.
_KINDS: dict[str, tuple[str, str]] = {
    "var": ("configuration", "Var"),
    "env": ("environment", "Env"),
    "eval": ("expression", "Eval"),
    "command": ("command", "Command"),
    "find-exec": ("paths", "FindExec"),
    "find-pkg-share": ("package", "FindPkgShare"),
    "find-pkg-prefix": ("package", "FindPkgPrefix"),
    "exec-in-pkg": ("package", "ExecInPkg"),
    "dirname": ("paths", "Dirname"),
    "filename": ("paths", "Filename"),
    "anon": ("configuration", "Anon"),
    "not": ("logic", "Not"),
    "and": ("logic", "And"),
    "or": ("logic", "Or"),
    "any": ("logic", "AnyOf"),
    "all": ("logic", "AllOf"),
    "equals": ("logic", "Equals"),
    "not-equals": ("logic", "NotEquals"),
    "if": ("logic", "IfElse"),
    "file-content": ("paths", "FileContent"),
    "log_dir": ("paths", "LogDir"),
    "launch_log_dir": ("paths", "LaunchLogDir"),
    "param": ("parameter", "Param"),
}
_MODULE_OF = {cls: module for module, cls in _KINDS.values()}


# a substitution class is imported with its module when first asked for
__getattr__ = lazy_attributes(__name__, {c: f".{m}" for c, m in _MODULE_OF.items()}, globals())


class _Registry(Mapping[str, "type[Call]"]):
    """``$(name ...)`` -> class, importing a kind's module the first time it is looked up."""

    def __getitem__(self, name: str) -> type[Call]:
        cls: type[Call] = __getattr__(_KINDS[name][1])
        return cls

    def __iter__(self) -> Iterator[str]:
        return iter(_KINDS)

    def __len__(self) -> int:
        return len(_KINDS)


#: ``$(name ...)`` -> class; the tokenizer rejects any other name.
SUBSTITUTIONS: Mapping[str, type[Call]] = _Registry()

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
