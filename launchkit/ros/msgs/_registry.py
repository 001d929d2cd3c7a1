"""Every interface type launchkit knows, found when first asked for, and its class and hash.

Three sources, in this order for a type name:

1. the built-in store: rosbags' ROS 2 Jazzy messages (read through :mod:`._defcache`) with their
   ``.msg`` defaults, and the services of :mod:`._builtin`;
2. the ``msg/``, ``srv/`` and ``action/`` folders of the package's share directory, found through
   the package index (an ament prefix's ``share/PKG/``, a registered launchkit package): every
   interface file of the package is read when the first of its types is asked for, and the types
   its fields use are looked up (in any package) then, so a mistake is reported at its line;
3. types registered by hand (:meth:`Registry.register`, a bag's own definitions).

Classes are made on first use, nested types first. RIHS01 hashes and the ``.msg`` text MCAP wants
come from rosbags' ``Typestore``, given the same definitions (``hash_rihs01``,
``generate_msgdef``); rosidl computes the same hashes from the same fields.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any, cast

from rosbags.typesys.store import Typestore

from launchkit.errors import Location, UserError
from launchkit.ros.msgs import _classes, _spec
from launchkit.ros.msgs._builtin import DEFAULTS, INTERFACES
from launchkit.ros.msgs._codec import Codec, CodecFunctions
from launchkit.ros.msgs._defcache import definitions
from launchkit.ros.msgs._interface_files import InterfaceFileError, Parsed, parse_interface
from launchkit.ros.msgs._packages import KINDS, InterfacePackages, interface_packages

_EXTENSIONS = {"msg": ".msg", "srv": ".srv", "action": ".action"}
_ACTION_SERVICES = ("_SendGoal", "_GetResult")


class MessageTypeError(UserError):
    """A message, service or action type name that does not exist (or is malformed)."""


class Registry:
    """The process's interface types (one per process: :func:`registry`)."""

    def __init__(self, index: Any = None) -> None:
        """``index``: the package index to find packages in (default: one made from the
        environment when first needed)."""
        self._lock = threading.RLock()
        self._specs: dict[str, _spec.MessageSpec] = {}
        self._services: set[str] = set()  # pkg/srv/Name and pkg/action/Name_SendGoal, ...
        self._actions: set[str] = set()
        self._loaded_packages: set[str] = set()
        self._parsed_builtins: set[str] = set()
        # interface files that could not be read: the error is raised when they are used, so
        # that one bad file does not hide the rest of its package
        self._broken: dict[str, InterfaceFileError] = {}
        self._builtin_packages: set[str] | None = None
        self._classes: dict[str, Any] = {}
        self._codecs: dict[str, Codec] = {}
        self._jazzy: dict[str, Any] | None = None
        self._packages = interface_packages() if index is None else InterfacePackages(index)
        self._hashes: dict[str, str] = {}
        self._definitions = Typestore()  # rosbags' hash and .msg text, from our definitions
        self.functions = CodecFunctions(self.spec, self.message_class, _classes.CHECK_FIELDS)

    # -- definitions -------------------------------------------------------------------------

    def jazzy(self) -> dict[str, Any]:
        """rosbags' Jazzy message definitions (``{name: (constants, fields)}``)."""
        if self._jazzy is None:
            self._jazzy = definitions()
        return self._jazzy

    def spec(self, name: str) -> _spec.MessageSpec:
        """The spec of message type ``name`` (a message, or a service's or action's part);
        KeyError if no source has it."""
        found = self._specs.get(name)
        if found is not None:
            return found
        with self._lock:
            self._find(name)
            return self._specs[name]

    def has(self, name: str) -> bool:
        """Whether a message type, service or action ``name`` exists (looking it up)."""
        with self._lock:
            try:
                self._find(name)
            except (KeyError, ValueError):
                return False
            return name in self._specs

    def _find(self, name: str) -> None:
        if name in self._specs:
            return
        pkg, kind, short = name.split("/")
        if kind == "msg" and name in self.jazzy():
            self._specs[name] = _spec.spec_from_typesdict(
                name, self.jazzy()[name], DEFAULTS.get(name)
            )
            return
        interface = f"{pkg}/{kind}/{_classes.interface_stem(kind, short)}"
        if interface in INTERFACES:
            if interface not in self._parsed_builtins:
                self._parsed_builtins.add(interface)
                text, path = INTERFACES[interface], f"<built-in {interface}>"
                parsed = parse_interface(text, interface, path)
                self._add(parsed, interface, kind)
                self._check_references(parsed)
        elif pkg not in self.builtin_packages():
            self._load_package(pkg)
        broken = self._broken.get(interface)
        if broken is not None:
            raise broken
        if name not in self._specs:
            raise KeyError(name)

    def _add(self, parsed: Parsed, interface: str, kind: str) -> None:
        for name, spec in parsed.specs.items():
            self._specs.setdefault(name, spec)
        if kind == "srv":
            self._services.add(interface)
        elif kind == "action":
            self._actions.add(interface)
            self._services.update(interface + suffix for suffix in _ACTION_SERVICES)

    def _check_references(self, parsed: Parsed) -> None:
        for reference in parsed.references:
            try:
                self._find(reference.type_name)
            except InterfaceFileError:
                raise
            except (KeyError, ValueError):
                raise InterfaceFileError(
                    f"unknown message type {reference.type_name!r}",
                    reference.location,
                    expected="a type of this package, of a package in AMENT_PREFIX_PATH or a "
                    "built-in ROS 2 Jazzy type such as std_msgs/Header",
                ) from None

    def index(self) -> Any:
        """The package index (made on first use, from the environment as it is then)."""
        return self._packages.index()

    def package_folder(self, pkg: str, registered: bool = True) -> Path | None:
        """The share directory of ``pkg`` if it has interface folders (``registered``: also
        look at packages registered by Python distributions, which costs a first lookup)."""
        return self._packages.folder(pkg, registered)

    def _load_package(self, pkg: str) -> None:
        if pkg in self._loaded_packages:
            return
        self._loaded_packages.add(pkg)
        share = self.package_folder(pkg)
        if share is None:
            return
        parsed_files = []
        for kind in KINDS:
            folder = share / kind
            if not folder.is_dir():
                continue
            for path in sorted(folder.glob("*" + _EXTENSIONS[kind])):
                interface = f"{pkg}/{kind}/{path.stem}"
                try:
                    text = path.read_text(encoding="utf-8")
                    parsed = parse_interface(text, interface, str(path))
                except (OSError, UnicodeDecodeError) as exc:
                    self._broken[interface] = InterfaceFileError(
                        f"cannot read the interface file: {exc}", Location(str(path))
                    )
                    continue
                except InterfaceFileError as exc:
                    self._broken[interface] = exc
                    continue
                self._add(parsed, interface, kind)
                parsed_files.append((interface, parsed))
        for interface, parsed in parsed_files:
            try:
                self._check_references(parsed)
            except InterfaceFileError as exc:
                self._broken[interface] = exc
                for name in parsed.specs:
                    self._specs.pop(name, None)
                self._services.discard(interface)
                self._actions.discard(interface)

    def register(self, typesdict: dict[str, Any]) -> None:
        """Add message types given as rosbags' ``{name: (constants, fields)}`` (a bag's own
        definitions); types already known keep their definition."""
        with self._lock:
            for name, entry in typesdict.items():
                if not self.has(name):
                    self._specs[name] = _spec.spec_from_typesdict(name, entry)

    # -- names -------------------------------------------------------------------------------

    def is_service(self, name: str) -> bool:
        """Whether ``name`` is a service (``pkg/srv/Name`` or an action's ``_SendGoal`` ...)."""
        with self._lock:
            if name not in self._services:
                self.has(name)
            return name in self._services

    def is_action(self, name: str) -> bool:
        """Whether ``name`` is an action type (``pkg/action/Name``)."""
        with self._lock:
            if name not in self._actions:
                self.has(name)
            return name in self._actions

    def names(self, kind: str, packages: set[str] | None = None) -> list[str]:
        """Every known type of ``kind`` (``msg``: messages, ``srv``, ``action``), sorted; with
        ``packages``, the files of those packages are read first."""
        with self._lock:
            for pkg in (packages or set()) - self.builtin_packages():
                self._load_package(pkg)
            builtin = {n for n in INTERFACES if f"/{kind}/" in n}
            if kind == "msg":
                found = {*self.jazzy(), *builtin, *(n for n in self._specs if "/msg/" in n)}
            elif kind == "srv":
                found = {*builtin, *(n for n in self._services if "/srv/" in n)}
            else:
                found = {*builtin, *self._actions}
            if packages is not None:
                found = {n for n in found if n.split("/", 1)[0] in packages}
            return sorted(found)

    def discovered_packages(self) -> set[str]:
        """Every package of the package index with interface folders (not built in)."""
        names = set(self.index().names()) - self.builtin_packages()
        return {pkg for pkg in names if self.package_folder(pkg) is not None}

    def interface_members(self, interface: str) -> list[str]:
        """The types an interface file defines: ``pkg/srv/Name``, its ``_Request``, ...
        (an action: its parts and its two services)."""
        with self._lock:
            self.has(interface)
            pkg, kind, stem = interface.split("/")
            prefix = f"{pkg}/{kind}/"
            return sorted(
                name
                for name in self._specs
                if name.startswith(prefix)
                and _classes.interface_stem(kind, name[len(prefix) :]) == stem
            )

    def builtin_packages(self) -> set[str]:
        """The packages of the built-in store (their types come from it alone)."""
        if self._builtin_packages is None:
            self._builtin_packages = {n.split("/", 1)[0] for n in (*self.jazzy(), *INTERFACES)}
        return self._builtin_packages

    # -- classes, codecs, hashes -------------------------------------------------------------

    def message_class(self, name: str) -> Any:
        """The class of message type ``name`` (KeyError if unknown)."""
        found = self._classes.get(name)
        if found is not None:
            return found
        with self._lock:
            if name not in self._classes:
                spec = self.spec(name)
                for ref in _spec.referenced_types(spec):
                    self.message_class(ref)
                self._classes[name] = _classes.message_class(spec, self.message_class)
            return self._classes[name]

    def service_class(self, name: str) -> type[_classes.ServiceType]:
        """The class of service ``name`` (KeyError if unknown)."""
        with self._lock:
            if name not in self._classes:
                if not self.is_service(name):
                    raise KeyError(name)
                self._classes[name] = _classes.service_class(
                    name,
                    self.message_class(name + "_Request"),
                    self.message_class(name + "_Response"),
                    self.message_class(name + "_Event"),
                )
            found: type[_classes.ServiceType] = self._classes[name]
            return found

    def action_class(self, name: str) -> type[_classes.ActionType]:
        """The class of action ``name`` (KeyError if unknown)."""
        with self._lock:
            if name not in self._classes:
                if not self.is_action(name):
                    raise KeyError(name)
                self._classes[name] = _classes.action_class(
                    name,
                    {
                        "Goal": self.message_class(name + "_Goal"),
                        "Result": self.message_class(name + "_Result"),
                        "Feedback": self.message_class(name + "_Feedback"),
                        "SendGoalService": self.service_class(name + "_SendGoal"),
                        "GetResultService": self.service_class(name + "_GetResult"),
                        "FeedbackMessage": self.message_class(name + "_FeedbackMessage"),
                        "CancelGoalService": self.service_class("action_msgs/srv/CancelGoal"),
                        "GoalStatusMessage": self.message_class("action_msgs/msg/GoalStatusArray"),
                    },
                )
            found: type[_classes.ActionType] = self._classes[name]
            return found

    def codec(self, name: str) -> Codec:
        """The codec of message type ``name``."""
        found = self._codecs.get(name)
        if found is None:
            with self._lock:
                self.message_class(name)
                found = self._codecs.setdefault(name, Codec(name, self.functions))
        return found

    def type_hash(self, name: str) -> str:
        """The RIHS01 hash of a message, service or action type."""
        found = self._hashes.get(name)
        if found is None:
            with self._lock:
                self._define(name)
                found = self._hashes[name] = str(self._definitions.hash_rihs01(name))
        return found

    def message_definition(self, name: str) -> str:
        """The ``.msg`` text of a message type with its dependencies (for MCAP and Foxglove).

        rosbags writes ``.msg`` text for ``pkg/msg/`` types only; a service's or action's part
        (an action's ``_FeedbackMessage`` topic) is written with its types named
        ``pkg/msg/...``, which describes the same fields and bytes."""
        with self._lock:
            self._define(name)
            store = self._definitions
            if "/msg/" not in name:
                store = Typestore()
                for type_name, (consts, fields) in self._definitions.fielddefs.items():
                    renamed = [(f, _spec.desc_renamed(d, _as_msg)) for f, d in fields]
                    store.fielddefs[_as_msg(type_name)] = cast(Any, (consts, renamed))
            text, _ = store.generate_msgdef(_as_msg(name), ros_version=2)
            return str(text)

    def _define(self, name: str) -> None:
        """Give rosbags' store the definitions of ``name`` and of every type it uses."""
        todo = [name]
        while todo:
            current = todo.pop()
            if current in self._definitions.fielddefs:
                continue
            spec = self.spec(current)
            self._definitions.fielddefs[current] = cast(Any, spec.typesdict_entry())
            todo.extend(_spec.referenced_types(spec))


def _as_msg(type_name: str) -> str:
    pkg, _, short = type_name.split("/")
    return f"{pkg}/msg/{short}"


_registry: Registry | None = None
_registry_lock = threading.Lock()


def registry() -> Registry:
    """The process's registry."""
    global _registry
    if _registry is None:
        with _registry_lock:
            if _registry is None:
                _registry = Registry()
    return _registry
