"""The import hook: message packages as modules, ``PKG``, ``PKG.msg``, ``PKG.srv``, ``PKG.action``.

``PKG.msg`` holds the package's message classes (made when first read from the module),
``PKG.msg._name`` the classes of one interface file, as rosidl lays them out (a class's
``__module__``). Two ways in:

* ``launchkit.ros.msgs.PKG.msg``: always (:func:`install_launchkit_prefix`, run when
  ``launchkit.ros.msgs`` is imported), for every package launchkit knows;
* ``PKG.msg`` itself: after :func:`install`, which the ``rclpy`` face's ``sitecustomize`` calls
  when a process starts. One finder goes first on ``sys.meta_path``, so launchkit's ``std_msgs``
  shadows an installed one, for the built-in packages and those of ``AMENT_PREFIX_PATH``; another
  goes last, for packages registered by Python distributions, and is asked only about modules
  nothing else found (reading the registrations costs tens of milliseconds, and the first finder
  is asked about every import).
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import threading
import types
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from launchkit.ros.msgs._packages import BUILTIN_PACKAGES, KINDS, interface_packages

if TYPE_CHECKING:
    from launchkit.ros.msgs._registry import Registry

_PREFIX = "launchkit.ros.msgs."
#: Never message packages: the standard library's modules, and Jython's ``org`` (copy and pickle
#: of Python 3.11 try it). The standard library tries modules of other platforms (subprocess
#: tries msvcrt) in every process; asked about one, the last finder would read every installed
#: distribution's entry points (75 ms of CPU) in every node that starts.
_STANDARD_LIBRARY = frozenset(sys.stdlib_module_names) | {"org"}
_looking = threading.local()


class InterfaceFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds and makes the modules of message packages under ``prefix``."""

    def __init__(self, prefix: str, ament: bool, registered: bool) -> None:
        self.prefix = prefix
        self.ament = ament  # serve packages found in AMENT_PREFIX_PATH
        self.registered = registered  # serve packages registered by Python distributions

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith(self.prefix):
            return None
        parts = fullname[len(self.prefix) :].split(".")
        if len(parts) > 3 or parts[0].startswith("_"):
            return None
        if len(parts) > 1 and parts[1] not in KINDS:
            return None
        if len(parts) == 3 and not parts[2].startswith("_"):
            return None
        if not self._serves(parts[0]):
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=len(parts) == 1)

    def _serves(self, pkg: str) -> bool:
        if not pkg.isidentifier() or getattr(_looking, "busy", False):
            return False
        _looking.busy = True  # what finding out imports is not a message package
        try:
            return self._knows(pkg)
        finally:
            _looking.busy = False

    def _knows(self, pkg: str) -> bool:
        # from names and folders alone: the message layer loads when a package is imported
        if pkg in BUILTIN_PACKAGES:
            return True
        if pkg in _STANDARD_LIBRARY:
            return False
        packages = interface_packages()
        if self.ament and packages.folder(pkg, registered=False) is not None:
            return True
        return self.registered and packages.folder(pkg) is not None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        parts = module.__name__[len(self.prefix) :].split(".")
        if len(parts) == 1:
            module.__path__ = []
            return
        if len(parts) == 2:
            _fill_kind_module(module, parts[0], parts[1])
        else:
            _fill_interface_module(module, parts[0], parts[1], parts[2])


def registry() -> Registry:
    """The process's registry, loaded when a message package is first imported (not when the
    hook is installed: see :mod:`._packages`)."""
    from launchkit.ros.msgs._registry import registry as process_registry

    return process_registry()


def _lookup(type_name: str) -> Any:
    """The class of a message, service or action type."""
    reg = registry()
    if reg.is_action(type_name):
        return reg.action_class(type_name)
    if reg.is_service(type_name):
        return reg.service_class(type_name)
    return reg.message_class(type_name)


def _fill_kind_module(module: types.ModuleType, pkg: str, kind: str) -> None:
    """``PKG.msg``: every type of the package, each class made when first read."""
    prefix = f"{pkg}/{kind}/"
    names = {n[len(prefix) :] for n in registry().names(kind, {pkg}) if n.startswith(prefix)}

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {module.__name__!r} has no attribute {name!r}")
        value = _lookup(prefix + name)
        setattr(module, name, value)
        return value

    setattr(module, "__getattr__", __getattr__)  # noqa: B010 (PEP 562: a module's __getattr__)
    setattr(module, "__dir__", lambda: sorted({*names, *vars(module)}))  # noqa: B010
    setattr(module, "__all__", sorted(names))  # noqa: B010
    module.__path__ = []


def _fill_interface_module(module: types.ModuleType, pkg: str, kind: str, stem: str) -> None:
    """``PKG.msg._name``: the classes of one interface file (and their metaclasses), as
    rosidl's module has them."""
    from launchkit.ros.msgs._classes import snake_case

    prefix = f"{pkg}/{kind}/"
    for interface in registry().names(kind, {pkg}):
        if "_" + snake_case(interface[len(prefix) :]) == stem:
            for type_name in registry().interface_members(interface):
                found = _lookup(type_name)
                setattr(module, type_name.rsplit("/", 1)[1], found)
                setattr(module, type(found).__name__, type(found))
            return
    raise ImportError(f"no interface {stem[1:]!r} in {pkg}/{kind}", name=module.__name__)


_launchkit_prefix = InterfaceFinder(_PREFIX, ament=True, registered=True)
_first = InterfaceFinder("", ament=True, registered=False)
_last = InterfaceFinder("", ament=False, registered=True)


def install_launchkit_prefix() -> None:
    """Serve ``launchkit.ros.msgs.PKG.msg`` (once)."""
    if _launchkit_prefix not in sys.meta_path:
        sys.meta_path.append(_launchkit_prefix)


def install() -> None:
    """Serve ``PKG.msg``, ``PKG.srv`` and ``PKG.action`` for every package launchkit knows,
    ahead of any installed message package (once; call it when a process starts, before any
    message package is imported)."""
    install_launchkit_prefix()
    if _first not in sys.meta_path:
        sys.meta_path.insert(0, _first)
    if _last not in sys.meta_path:
        sys.meta_path.append(_last)
