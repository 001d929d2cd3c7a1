"""Package attributes imported when first asked for (PEP 562): one ``__getattr__`` for the two
packages every node process imports, ``launchkit`` (its API would load the launch engine, a
fifth of a node's start-up) and ``launchkit.ros`` (its node API would load the message types,
numpy and rosbags into the launcher, which imports only ``launchkit.ros.router``)."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy_attributes(
    package: str, where: Mapping[str, str], namespace: dict[str, Any]
) -> Callable[[str], Any]:
    """A module ``__getattr__`` for ``package``.

    ``where`` maps each public name to the module that defines it, ``"module"`` or
    ``"module:attribute"`` (a module starting with ``.`` is inside ``package``). The value is
    kept in ``namespace``, the package's globals, so that Python finds it there next time.
    """

    def __getattr__(name: str) -> Any:
        target = where.get(name)
        if target is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module, _, attribute = target.partition(":")
        if module.startswith("."):
            module = package + module
        value = getattr(importlib.import_module(module), attribute or name)
        namespace[name] = value
        return value

    return __getattr__
