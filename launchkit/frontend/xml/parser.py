"""Parse XML launch files (lxml keeps line numbers) into :class:`LaunchDescription`s."""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.xml.entity import SourceFile, XmlEntity


class XmlParser:
    """Parses XML launch text; the tags are read by ``actions``."""

    def __init__(self, actions: ActionParser) -> None:
        self.actions = actions

    def parse_file(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """Read and parse ``path``; ``included_from`` locates an error in reading it."""
        try:
            text = path.read_text()
        except OSError as error:
            raise LaunchFileError(
                f"cannot read '{path}': {error.strerror}", included_from
            ) from None
        return self.parse_text(text, path)

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
        entity = XmlEntity(root, source)
        if entity.tag != "launch":
            raise entity.error(
                f"the root element is <{entity.tag}>", expected="<launch> as the root element"
            )
        deprecated = entity.raw("deprecated")
        entity.assert_fully_read()
        return LaunchDescription(path, self.actions.parse_actions(entity), deprecated)
