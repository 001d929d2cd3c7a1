"""Makes ``launchkit.ros.msgs.<pkg>.msg`` and ``.srv`` importable, built from the typestore."""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import types
from collections.abc import Sequence

from launchkit.ros.msgs._api import get_message, get_service, packages, type_names

_PREFIX = "launchkit.ros.msgs."


class _Finder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds and creates the per-package modules (``pkg``, ``pkg.msg``, ``pkg.srv``)."""

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith(_PREFIX):
            return None
        parts = fullname[len(_PREFIX) :].split(".")
        if parts[0].startswith("_"):
            return None
        if parts[0] not in packages():
            return None
        if len(parts) == 1:
            return importlib.machinery.ModuleSpec(fullname, self, is_package=True)
        if len(parts) == 2 and parts[1] in ("msg", "srv"):
            return importlib.machinery.ModuleSpec(fullname, self)
        return None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        parts = module.__name__[len(_PREFIX) :].split(".")
        if len(parts) == 1:
            module.__path__ = []
            return
        pkg, kind = parts
        prefix = f"{pkg}/{kind}/"
        names = [name for name in type_names(kind) if name.startswith(prefix)]
        lookup = get_message if kind == "msg" else get_service
        for name in names:
            setattr(module, name[len(prefix) :], lookup(name))
        module.__all__ = [name[len(prefix) :] for name in names]  # type: ignore[attr-defined]


_finder = _Finder()


def install() -> None:
    """Add the finder to ``sys.meta_path`` once."""
    if _finder not in sys.meta_path:
        sys.meta_path.append(_finder)
