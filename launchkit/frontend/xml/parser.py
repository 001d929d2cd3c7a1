"""Load XML launch files (lxml keeps line numbers) into :class:`LaunchDescription`s."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import TAGS, parse_condition
from launchkit.frontend.tags import launch as _tags  # noqa: F401  (registers the tag parsers)
from launchkit.frontend.xml.entity import Entity, SourceFile

if TYPE_CHECKING:
    from launchkit.description.actions.base import Action

XML_SUFFIXES = (".xml", ".launch")


class XmlParser:
    """Parses launch files, caching each file's description by path."""

    def __init__(self) -> None:
        self._cache: dict[Path, LaunchDescription] = {}

    def load(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """The description of ``path``; errors carry the file, line and column."""
        path = path.resolve()
        cached = self._cache.get(path)
        if cached is not None:
            return cached
        if path.suffix == ".py" and path.is_file():
            from launchkit.frontend.python import load_python_launch

            description = load_python_launch(path, included_from)
            self._cache[path] = description
            return description
        if path.suffix not in XML_SUFFIXES:
            raise LaunchFileError(
                f"cannot read launch file '{path.name}'",
                included_from or Location(str(path)),
                expected="an XML launch file (*.launch.xml, *.xml, *.launch) "
                "or a Python one (*.launch.py)",
                hint="YAML launch files are not supported",
            )
        try:
            text = path.read_text()
        except OSError as error:
            raise LaunchFileError(
                f"cannot read '{path}': {error.strerror}", included_from
            ) from None
        description = self.parse_text(text, path)
        self._cache[path] = description
        return description

    def parse_text(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch XML ``text`` as if read from ``path``."""
        source = SourceFile(path, text)
        parser = etree.XMLParser(remove_comments=True, remove_pis=True, resolve_entities=False)
        try:
            root = etree.fromstring(text.encode(), parser)
        except etree.XMLSyntaxError as error:
            line, col = error.position
            message = str(error.msg or error).split(", line ")[0]
            raise LaunchFileError(
                f"malformed XML: {message}",
                Location(str(path), line, col),
                expected="well-formed XML",
            ) from None
        entity = Entity(root, source)
        if entity.tag != "launch":
            raise entity.error(
                f"the root element is <{entity.tag}>", expected="<launch> as the root element"
            )
        deprecated = entity.raw("deprecated")
        entity.assert_fully_read()
        return LaunchDescription(path, self.parse_actions(entity), deprecated)

    def parse_actions(self, parent: Entity, skip: tuple[str, ...] = ()) -> list[Action]:
        """The actions among ``parent``'s children (tags in ``skip`` are left to the parent)."""
        return [self.parse_action(child) for child in parent.children() if child.tag not in skip]

    def parse_action(self, entity: Entity) -> Action:
        """One action tag, with its condition, fully checked."""
        parse = TAGS.get(entity.tag)
        if parse is None:
            raise entity.error(
                f"unknown tag <{entity.tag}>",
                expected="one of: " + ", ".join(sorted(TAGS)),
                hint=_hint(entity.tag),
            )
        condition = parse_condition(entity)
        action = parse(entity, self)
        action.condition = condition
        action.location = entity.location
        entity.assert_fully_read()
        return action


_ROS1_HINTS = {
    "rosparam": 'ROS 2 has no <rosparam>; use <param from="file.yaml"/> inside <node>',
    "machine": "ROS 2 has no <machine>",
    "test": "ROS 2 has no <test>; see launchkit.testing",
    "env": "use <set_env> at this level; <env> belongs inside <executable> or <node>",
}


def _hint(tag: str) -> str | None:
    return _ROS1_HINTS.get(tag)
