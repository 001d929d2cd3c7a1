"""An XML launch file read as a stream: each top-level element becomes its action as soon as
its end tag is read, and is then dropped from lxml's tree, so a large file never has its whole
tree (nor its whole text, which is kept only for the lines columns are still looked up in)
in memory.

Errors keep their precedence: an action's error is held while the rest of the file is read,
and a file that turns out not to be well-formed is read again whole, whose parser reports the
syntax error exactly as before (see :class:`~launchkit.frontend.xml.parser.XmlParser`).
"""

from __future__ import annotations

import codecs
import re
from pathlib import Path
from typing import Any

from lxml import etree

from launchkit.description.actions.base import Action
from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.xml.entity import LINES_BACK, SourceFile, XmlEntity, read_root

#: How many bytes are read and parsed at a time.
CHUNK_SIZE = 256 * 1024
#: lxml's options for launch files: no comments or processing instructions in the tree, and
#: no entity expanded (no XXE, no "billion laughs"); lxml's default ``no_network`` stays on.
PARSER_OPTIONS: dict[str, Any] = {
    "remove_comments": True,
    "remove_pis": True,
    "resolve_entities": False,
}
DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


class NotStreamable(Exception):
    """The file's encoding is not one the stream decodes alongside lxml (UTF-16, or one
    Python does not know): it is read whole instead."""


class ElementStream:
    """Feeds a file's bytes to lxml and parses each top-level element as it completes."""

    def __init__(self, actions: ActionParser, path: Path) -> None:
        self.actions = actions
        self.path = path
        # end events only: an element is complete there, and no proxy is made for its start
        self.parser = etree.XMLPullParser(events=("end",), **PARSER_OPTIONS)
        self.source = SourceFile(path)
        self.decoder: codecs.IncrementalDecoder | None = None
        self.encoding = ""
        self.root: etree._Element | None = None
        self.deprecated: str | None = None
        self.parsed: list[Action] = []
        self.error: LaunchFileError | None = None  # the first, raised once the file is read
        self.keep_from = 1  # the line of the last top-level element parsed

    def feed(self, chunk: bytes) -> None:
        """Read the next bytes and parse the top-level elements they complete."""
        if self.decoder is None:
            self.encoding = _stream_encoding(chunk)
            self.decoder = codecs.getincrementaldecoder(self.encoding)("replace")
        self.source.forget_before(self.keep_from - LINES_BACK)
        try:
            self.source.append(self.decoder.decode(chunk))
        except UnicodeError:  # a codec that fails even with "replace" (UTF-16 without a BOM)
            raise NotStreamable(self.encoding) from None
        self.parser.feed(chunk)
        self._read_events()

    def close(self) -> LaunchDescription:
        """The end of the file: its description, or the first error in it."""
        if self.decoder is not None:
            self.source.append(self.decoder.decode(b"", True))
        self.parser.close()  # a syntax error (an empty file, an unclosed tag) is raised here
        self._read_events()
        if self.error is not None:
            raise self.error
        return LaunchDescription(self.path, self.parsed, self.deprecated)

    def _read_events(self) -> None:
        element: etree._Element
        parse, parsed, source = self.actions.parse_action, self.parsed, self.source
        for _, element in self.parser.read_events():  # type: ignore[assignment]
            parent = element.getparent()
            if parent is None:  # the root's end: the file's last element
                if self.root is None:
                    self._start_root(element)
                continue
            if parent is not self.root:
                if parent.getparent() is not None:  # inside a top-level element
                    continue
                if self.root is None:
                    self._start_root(parent)
            # a top-level element (one per action: a large file's loop, kept inline)
            tag = element.tag
            if self.error is None and isinstance(tag, str):
                sourceline: int | None = element.sourceline  # type: ignore[assignment]
                try:
                    parsed.append(parse(XmlEntity(element, source, sourceline, tag)))
                except LaunchFileError as error:
                    self.error = error  # raised at the end, unless the file is not well-formed
                self.keep_from = sourceline or self.keep_from
            parent.remove(element)  # its action holds no part of it: the tree stays small

    def _start_root(self, root: etree._Element) -> None:
        """The root, met at its first child's end (its attributes are all read by then)."""
        declared = root.getroottree().docinfo.encoding or "utf-8"
        if _codec_name(declared) != _codec_name(self.encoding):
            raise NotStreamable(declared)
        self.root = root
        try:
            self.deprecated = read_root(XmlEntity(root, self.source))
        except LaunchFileError as error:
            self.error = error


def _stream_encoding(head: bytes) -> str:
    """The encoding the file's text is decoded in alongside lxml (for columns): the one its
    declaration names, else UTF-8 (a UTF-8 byte order mark stays a character, as lxml counts
    it); NotStreamable for UTF-16 and UTF-32, and for an encoding Python does not know."""
    if head.startswith((b"\xff\xfe", b"\xfe\xff")) or b"\x00" in head[:4]:
        raise NotStreamable("UTF-16 or UTF-32")
    declared = DECLARED_ENCODING.match(head[:200])
    encoding = declared.group(1).decode() if declared else "utf-8"
    if _codec_name(encoding).startswith(("utf-16", "utf-32")):  # the declaration was ASCII
        raise NotStreamable(encoding)
    return encoding


def _codec_name(encoding: str) -> str:
    try:
        return codecs.lookup(encoding).name
    except LookupError:
        raise NotStreamable(encoding) from None
