"""Static checks: everything that can be known wrong before a single process starts.

Parsing already rejects unknown tags, attributes and substitutions, malformed substitutions and
bad literal values. On top of that this module loads every ``<include>`` whose path is known
without running anything (one under an ``if``/``unless`` that fails to load is no error: ROS
reads it the same way for its arguments and reports nothing; the include reports it if and when
it runs), and checks the command-line arguments against the top file's ``<arg>`` declarations
(required ones present, values among the choices).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields, is_dataclass
from pathlib import Path

from launchkit.description.actions import DeclareArgument, Include
from launchkit.description.actions.base import Action
from launchkit.description.launch_description import LaunchDescription, walk
from launchkit.description.substitutions import (
    Dirname,
    Filename,
    FindPkgPrefix,
    FindPkgShare,
    Substitution,
    Text,
    Var,
)
from launchkit.description.substitutions.base import literal
from launchkit.errors import (
    LaunchArgumentError,
    LaunchFileError,
    LaunchkitError,
    Location,
    PackageNotFoundError,
)
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.packages import PackageIndex, exists, is_file


class CheckedTree:
    """The top description and every statically included one."""

    def __init__(self, top: LaunchDescription) -> None:
        self.top = top
        self.files: dict[Path, LaunchDescription] = {top.path: top}

    @property
    def entity_count(self) -> int:
        """How many actions the checked files hold."""
        return sum(len(walk(d.actions)) for d in self.files.values())

    def has_conditions(self) -> bool:
        """Whether any action of the checked files has an ``if`` or ``unless``."""
        return any(
            action.condition is not None
            for description in self.files.values()
            for action in walk(description.actions)
        )


def parse_launch_arguments(items: list[str]) -> dict[str, str]:
    """``name:=value`` items into a dict (last wins, values keep spaces)."""
    values: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep:
            raise LaunchArgumentError(
                f"{item!r} is not a launch argument assignment",
                expected="NAME:=VALUE",
                hint=f"did you mean '{item.replace('=', ':=', 1)}'?" if "=" in item else None,
            )
        if not name.strip():
            raise LaunchArgumentError(f"malformed launch argument {item!r}", expected="NAME:=VALUE")
        values[name] = value
    return values


def check_tree(
    path: Path,
    arguments: Mapping[str, str] | None,
    loader: LaunchLoader,
    packages: PackageIndex,
) -> CheckedTree:
    """Parse ``path`` and its static includes and check ``arguments`` (unless None, as for
    ``--show-args``); raise on the first error."""
    tree = CheckedTree(loader.load(path))
    chains: dict[Path, list[Location]] = {tree.top.path: []}  # the includes that led to a file
    pending = [tree.top]
    while pending:
        description = pending.pop()
        chain = chains[description.path]
        for action in walk(description.actions):
            if not isinstance(action, Include):
                continue
            included = static_path(action, description.path, packages)
            if included is None or included in tree.files:
                continue
            always = _always_runs(action, description)
            try:
                if not is_file(included):
                    if always:
                        raise LaunchFileError(
                            f"included launch file '{included}' does not exist",
                            action.location,
                            expected="a path to a launch file",
                        )
                    continue  # conditional: reported if and when the include runs
                child = loader.load(included, action.location, action.syntax)
            except LaunchkitError as error:
                if not always:
                    # As ROS's look for declared arguments: a file under an if/unless is read
                    # (a Python one's code runs), and what fails is reported only if and when
                    # the include runs
                    continue
                for place in reversed([*chain, action.location]):
                    if place is not None:
                        error.included_from(place)
                raise
            tree.files[included] = child
            chains[child.path] = [*chain, *([action.location] if action.location else [])]
            pending.append(child)
    if arguments is not None:
        check_arguments(tree.top, arguments)
    return tree


def _always_runs(target: Action, description: LaunchDescription) -> bool:
    """Whether ``target`` sits under no ``if``/``unless`` (itself included)."""

    def search(actions: list[Action], guarded: bool) -> bool | None:
        for action in actions:
            here = guarded or action.condition is not None
            if action is target:
                return not here
            found = search(list(action.children()), here)
            if found is not None:
                return found
        return None

    return bool(search(description.actions, False))


def static_path(include: Include, current: Path, packages: PackageIndex) -> Path | None:
    """The included file when its path needs nothing but text, ``$(dirname)``, ``$(filename)``
    and package lookups; None when it depends on the run."""
    parts: list[str] = []
    for part in include.file:
        text = _static_text(part, current, packages)
        if text is None:
            return None
        parts.append(text)
    path = Path("".join(parts))
    if not path.is_absolute() and not exists(path):
        path = current.parent / path
    return path.resolve()


def _static_text(part: Substitution, current: Path, packages: PackageIndex) -> str | None:
    if isinstance(part, Text):
        return part.text
    if isinstance(part, Dirname):
        return str(current.parent)
    if isinstance(part, Filename):
        return str(current)
    if isinstance(part, FindPkgShare | FindPkgPrefix):
        name = literal(part.args[0])
        if name is None:
            return None
        try:
            found = packages.find(name)
        except PackageNotFoundError:
            return None  # reported when (and if) the include runs
        return str(found.share if isinstance(part, FindPkgShare) else found.prefix)
    return None


def check_arguments(top: LaunchDescription, arguments: Mapping[str, str]) -> None:
    """Required top-level arguments are given and given values are among the choices."""
    for required in top.required_arguments():
        if required.name not in arguments:
            raise required.missing_error()
    for declared in top.declared_arguments():
        value = arguments.get(declared.name)
        if value is not None:
            declared.check_choice(value)
        elif declared.default is not None and declared.condition is None:
            default = literal(declared.default)
            if default is not None:
                declared.check_choice(default)


def undeclared_arguments(tree: CheckedTree, arguments: Mapping[str, str]) -> list[str]:
    """Command-line names no checked file declares or reads with a literal ``$(var NAME)``."""
    known: set[str] = set()
    for description in tree.files.values():
        for action in walk(description.actions):
            if isinstance(action, DeclareArgument):
                known.add(action.name)
            for value in vars(action).values():
                known.update(_var_names(value))
    return [name for name in arguments if name not in known and name not in _SPECIAL]


_SPECIAL = {
    "sigterm_timeout",
    "sigkill_timeout",
    "launch-prefix",
    "launch-prefix-filter",
    "emulate_tty",
    "ros_namespace",
}


def _var_names(value: object) -> set[str]:
    names: set[str] = set()
    if isinstance(value, tuple | list):
        for item in value:
            names |= _var_names(item)
    elif isinstance(value, Var):
        name = literal(value.args[0])
        if name is not None:
            names.add(name)
    elif hasattr(value, "args") and isinstance(value, Substitution):
        names |= _var_names(getattr(value, "args", ()))
    elif is_dataclass(value):  # a condition, an include's <arg>, a <keep>, a node's <param>
        names |= _var_names([getattr(value, field.name) for field in fields(value)])
    return names
