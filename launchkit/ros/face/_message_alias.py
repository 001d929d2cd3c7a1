"""Serves ``PKG.msg`` and ``PKG.srv`` as aliases of ``launchkit.ros.msgs.PKG.msg`` (and
``.srv``), ahead of installed message packages: the face's import hook for a
``launchkit.ros.msgs`` that offers no ``install()`` of its own."""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
from collections.abc import Sequence

_KINDS = ("msg", "srv")


class _AliasFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """``PKG.msg`` is ``launchkit.ros.msgs.PKG.msg`` (a bare ``PKG`` only when nothing else
    provides it: this finder is also last on ``sys.meta_path``)."""

    def __init__(self, submodules_only: bool) -> None:
        self.submodules_only = submodules_only

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        parts = fullname.split(".")
        if len(parts) > 2 or (len(parts) == 2 and parts[1] not in _KINDS):
            return None
        if self.submodules_only and len(parts) == 1:
            return None
        from launchkit.ros.msgs import packages

        if parts[0] not in packages():
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=len(parts) == 1)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        if spec.name.count(".") == 1:
            return importlib.import_module("launchkit.ros.msgs." + spec.name)
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        if "." not in module.__name__:
            module.__path__ = []


def install_alias() -> None:
    """Put the alias finders first and last on ``sys.meta_path`` (once)."""
    if not any(isinstance(f, _AliasFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _AliasFinder(submodules_only=True))
        sys.meta_path.append(_AliasFinder(submodules_only=False))
