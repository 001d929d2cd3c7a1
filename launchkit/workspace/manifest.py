"""A package's ``package.xml`` (formats 1 to 3, REP 127/140/149) read with lxml, every
dependency with the place it was written, so an error can point at it.

Only what building needs is read: the name, the version, the build type
(``<export><build_type>``; none means ``catkin``, as colcon takes it), the dependencies of each
kind, the groups the package belongs to and the groups it depends on. ``condition``
attributes are evaluated (see :mod:`launchkit.workspace.conditions`): a dependency whose
condition does not hold is dropped.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from launchkit.errors import Location, UserError
from launchkit.workspace.conditions import ConditionError, condition_context, evaluate

#: Dependency kinds, as the tags name them (``run_depend`` is format 1's ``exec_depend``).
DEPENDENCY_TAGS = (
    "depend",
    "build_depend",
    "build_export_depend",
    "buildtool_depend",
    "buildtool_export_depend",
    "exec_depend",
    "run_depend",
    "test_depend",
    "doc_depend",
)
#: A package name that is safe as a folder name (REP 140 asks for less: lower case, digits
#: and underscores; dashes and capitals are let through as colcon does).
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*\Z")


class ManifestError(UserError):
    """A package.xml that cannot be read or says something impossible (exit status 2)."""


@dataclass(frozen=True)
class Dependency:
    """One dependency tag: the package it names, its kind (the tag) and where it is written."""

    name: str
    kind: str
    location: Location


@dataclass(frozen=True)
class Manifest:
    """What a package.xml says, and where the package's folder is."""

    name: str
    version: str
    build_type: str
    path: Path
    dependencies: tuple[Dependency, ...]
    groups: tuple[str, ...]
    group_depends: tuple[str, ...]
    location: Location

    @property
    def manifest_path(self) -> Path:
        """The package.xml file."""
        return self.path / "package.xml"

    def depends(self, *kinds: str) -> list[Dependency]:
        """The dependencies of these kinds (``depend`` counts as build, export and exec)."""
        return [d for d in self.dependencies if d.kind in kinds]


def read_manifest(path: Path, environ: Mapping[str, str] | None = None) -> Manifest:
    """The package.xml at ``path``; :class:`ManifestError` with ``file:line:col`` if it is
    malformed (not XML, not a ``<package>``, no ``<name>``, a bad condition)."""
    shown = _shown(path)
    try:
        tree = etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True))
    except etree.XMLSyntaxError as error:
        line, col = error.position
        raise ManifestError(
            f"not well-formed XML: {error.msg}", Location(shown, line, col)
        ) from None
    except OSError as error:
        raise ManifestError(f"cannot read: {error}", Location(shown)) from None
    root = tree.getroot()
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    where = _Locator(shown, lines)
    if root.tag != "package":
        raise ManifestError(
            f"the root element is <{root.tag}>", where(root), expected="<package format=...>"
        )
    context = condition_context(os.environ if environ is None else environ)
    name = _text(root, "name")
    if not name:
        raise ManifestError("no <name>", where(root), expected="<name>the_package</name>")
    if not _NAME.match(name) or name in (".", ".."):
        raise ManifestError(
            f"package name {name!r} is not a valid package name",
            where(root.find("name")),
            expected="letters, digits and underscores",
        )
    dependencies = []
    for element in _children(root, DEPENDENCY_TAGS):
        if _inner(element) and _holds(element, context, where):
            kind = "exec_depend" if element.tag == "run_depend" else str(element.tag)
            dependencies.append(Dependency(_inner(element), kind, where(element)))
    groups = [
        _inner(e)
        for e in _children(root, ("member_of_group",))
        if _inner(e) and _holds(e, context, where)
    ]
    group_depends = [
        _inner(e)
        for e in _children(root, ("group_depend",))
        if _inner(e) and _holds(e, context, where)
    ]
    return Manifest(
        name=name,
        version=_text(root, "version"),
        build_type=_build_type(root, context, where),
        path=path.parent,
        dependencies=tuple(dependencies),
        groups=tuple(groups),
        group_depends=tuple(group_depends),
        location=where(root),
    )


def _shown(path: Path) -> str:
    """The path as an error shows it: relative to the working folder when inside it."""
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


class _Locator:
    """``file:line:col`` of an element: lxml knows its line; the column is where its start
    tag begins on that line."""

    def __init__(self, shown: str, lines: list[str]) -> None:
        self.shown = shown
        self.lines = lines

    def __call__(self, element: etree._Element | None) -> Location:
        line = element.sourceline if element is not None else None
        if element is None or not isinstance(line, int) or line <= 0:
            return Location(self.shown)
        text = self.lines[line - 1] if line <= len(self.lines) else ""
        col = text.find(f"<{element.tag}")
        return Location(self.shown, line, col + 1 if col >= 0 else 0)


def _children(root: etree._Element, tags: tuple[str, ...]) -> list[etree._Element]:
    return [child for child in root if isinstance(child.tag, str) and child.tag in tags]


def _text(root: etree._Element, tag: str) -> str:
    element = root.find(tag)
    return _inner(element) if element is not None else ""


def _inner(element: etree._Element) -> str:
    """An element's text, stripped (empty when it has none)."""
    return (element.text or "").strip()


def _holds(element: etree._Element, context: Mapping[str, str], where: _Locator) -> bool:
    condition = element.get("condition")
    if condition is None:
        return True
    try:
        return evaluate(condition, context)
    except ConditionError as error:
        raise ManifestError(str(error), where(element)) from None


def _build_type(root: etree._Element, context: Mapping[str, str], where: _Locator) -> str:
    export = root.find("export")
    if export is not None:
        for element in _children(export, ("build_type",)):
            if _inner(element) and _holds(element, context, where):
                return _inner(element)
    return "catkin"  # what colcon (catkin_pkg) assumes of a package.xml without one
