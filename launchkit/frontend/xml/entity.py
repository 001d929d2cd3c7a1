"""One XML element as the tag parsers see it: attributes with the line and column they were
written at (expat or lxml gives the line; the column is found in the source text)."""

from __future__ import annotations

import bisect
import functools
import re
from collections.abc import Iterator
from itertools import accumulate, count
from operator import add
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Text, Value
from launchkit.description.substitutions.grammar import parse_value
from launchkit.errors import Location
from launchkit.frontend.base_entity import Entity

if TYPE_CHECKING:
    from lxml import etree

    from launchkit.frontend.xml.expat_tree import Element

    #: An element as expat (a small plain file) or lxml (any other) read it.
    AnyElement = Element | etree._Element

#: How many lines before an element's reported line its start tag may begin (lxml gives the
#: line where the start tag ends; expat the line where it begins).
LINES_BACK = 20
#: What may follow ``<tag`` in a start tag (``<tagname`` is another tag); "" is the text's end.
_TAG_ENDS = frozenset([" ", "\t", "\n", "\r", "/", ">", ""])
#: The longest attribute text whose value elements share, and how many texts a file shares
#: (the first ones met: ``true``, ``screen``, a package name recur; most names do not).
SHARED_LENGTH = 24
SHARED_VALUES = 1024
#: ``="`` or ``='``: an attribute written as most are, without blanks around its ``=``.
_EQUALS_QUOTE = frozenset(['="', "='"])


@functools.lru_cache(maxsize=256)
def _attribute_pattern(name: str) -> re.Pattern[str]:
    """Finds ``NAME = "`` (starting with the name: a literal the search jumps to)."""
    return re.compile(re.escape(name) + r"\s*=\s*([\"'])")


def _line_starts(text: str, start: int) -> Iterator[int]:
    """Where the lines after each newline of ``text`` start, ``text`` being at offset
    ``start`` (C-level iteration: a large file has one line per element)."""
    lengths = accumulate(map(len, text.split("\n")[:-1]))  # the text before each newline
    return map(add, lengths, count(start + 1))  # and the newlines up to and with it


class SourceFile:
    """A launch file's path and the part of its text still needed for columns in messages:
    all of it, or, when the file is read as a stream, a window of whole lines that grows as
    text is read and is cut from the front once the elements there are done."""

    __slots__ = ("file", "first_line", "line_starts", "path", "plain_values", "text")

    def __init__(self, path: Path, text: str = "") -> None:
        self.path = path
        self.file = str(path)  # one string shared by every location in the file
        self.text = text  # the window: whole lines from ``first_line`` on
        self.first_line = 1
        #: Where each line of the window starts (offsets into ``text``).
        self.line_starts = [0, *_line_starts(text, 0)]
        #: The values of short attributes without substitutions, shared by the elements
        #: that write the same text (``if="false"``, ``output="screen"``; values are never
        #: changed once parsed): one object, and no new one made, per element of a large file.
        self.plain_values: dict[str, Value] = {}

    def append(self, text: str) -> None:
        """Text read after the window's end."""
        start = len(self.text)
        self.text += text
        self.line_starts.extend(_line_starts(text, start))

    def forget_before(self, line: int) -> None:
        """Drop the text before 1-based ``line`` (offsets into the window change)."""
        index = min(line - self.first_line, len(self.line_starts) - 1)
        if index <= 0:
            return
        cut = self.line_starts[index]
        self.text = self.text[cut:]
        self.line_starts = [start - cut for start in self.line_starts[index:]]
        self.first_line += index

    def line_span(self, line: int) -> tuple[int, int]:
        """Offsets in the window where 1-based ``line`` starts and ends (clamped)."""
        starts = self.line_starts
        index = min(max(line - self.first_line, 0), len(starts) - 1)
        return starts[index], starts[index + 1] if index + 1 < len(starts) else len(self.text)

    def offset(self, line: int) -> int:
        """Offset in the window where 1-based ``line`` starts (clamped to the window)."""
        index = min(max(line - self.first_line, 0), len(self.line_starts) - 1)
        return self.line_starts[index]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of an offset in the window."""
        index = max(bisect.bisect_right(self.line_starts, offset) - 1, 0)
        return index + self.first_line, offset - self.line_starts[index] + 1

    def location(self, offset: int) -> Location:
        """The location of an offset in the window."""
        line, col = self.position(offset)
        return Location(self.file, line, col)


class XmlEntity(Entity):
    """An element of an XML launch file."""

    def __init__(
        self,
        element: AnyElement,
        source: SourceFile,
        sourceline: int | None = None,
        tag: str | None = None,
    ) -> None:
        # Entity.__init__'s fields set here: a large file makes one of these per element
        if tag is None:  # (``tag``: the element's, when the caller has read it already)
            tag = element.tag
            if not isinstance(tag, str):
                tag = str(tag)
        self.tag = tag
        self._read: set[str] = set()
        self.element = element
        self.source = source
        self._attributes: dict[str, str] = dict(element.items())  # type: ignore[arg-type]
        if sourceline is None:
            sourceline = element.sourceline  # type: ignore[assignment]
        line: int = sourceline or 1
        self._location: Location | None = None
        # the usual case inline (see _find_start): the start tag begins on the line given
        starts = source.line_starts
        index = line - source.first_line
        if 0 <= index < len(starts) - 1:
            start = starts[index]
            text = source.text
            found = text.rfind("<" + tag, start, starts[index + 1])
            after = found + len(tag) + 1
            if found >= 0 and text[after : after + 1] in _TAG_ENDS:
                self._start = found
                self._line = line
                self._col = found - start + 1
                return
        self._start, self._line, self._col = self._find_start(line)

    def _find_start(self, line: int) -> tuple[int, int, int]:
        """The offset in the window, line and column where the start tag begins (``line``:
        the line lxml or expat gives)."""
        source = self.source
        starts = source.line_starts
        text = source.text
        index = line - source.first_line
        last = len(starts) - 1
        if 0 <= index < last:  # the line is whole in the window (the usual case)
            start, end = starts[index], starts[index + 1]
        else:
            start, end = source.line_span(line)
        opening = "<" + self.tag
        after = len(opening)
        # lxml reports the line where the start tag ends: most start tags begin on it too
        found = text.rfind(opening, start, end)
        if found >= 0 and (text[found + after : found + after + 1] in _TAG_ENDS):
            return found, line, found - start + 1
        # else search back a few lines for "<tag"
        search_from = source.offset(line - LINES_BACK)
        while True:
            found = text.rfind(opening, search_from, end)
            if found < 0:
                return start, line, 1
            if text[found + after : found + after + 1] in _TAG_ENDS:
                return (found, *source.position(found))
            end = found

    @property
    def location(self) -> Location:
        """Where the element's start tag begins."""
        if self._location is None:
            self._location = Location(self.source.file, self._line, self._col)
        return self._location

    def attribute_location(self, name: str) -> Location:
        """Where attribute ``name``'s value begins (after the quote)."""
        text = self.source.text
        position = self._start
        # the first NAME = " after a blank; the usual NAME=" found without the pattern (the
        # first NAME in the text is where the pattern's first match would be, if it matches)
        found = text.find(name, position)
        if found > 0 and text[found - 1].isspace():
            end = found + len(name) + 2
            if text[end - 2 : end] in _EQUALS_QUOTE:
                if text.find("\n", position, end) < 0:  # on the start tag's first line
                    return Location(self.source.file, self._line, self._col + end - position)
                return self.source.location(end)
        pattern = _attribute_pattern(name)
        while True:
            match = pattern.search(text, position)
            if match is None:
                return self.location
            if text[match.start() - 1].isspace():
                end = match.end()
                if text.find("\n", self._start, end) < 0:  # on the start tag's first line
                    return Location(self.source.file, self._line, self._col + end - self._start)
                return self.source.location(end)
            position = match.start() + 1

    def attribute_names(self) -> list[str]:
        """The element's attribute names."""
        return list(self._attributes)

    def attribute_text(self, name: str) -> str | None:
        """The attribute's text as lxml read it (entities and character references resolved)."""
        return self._attributes.get(name)

    def raw(self, name: str, native: str | None = None) -> str | None:
        """Attribute text as written (marks it read); XML has no typed values."""
        self._read.add(name)  # as Entity.raw does, a call shorter (a large file's hot path)
        return self._attributes.get(name)

    def value(self, name: str, native: str | None = None) -> Value | None:
        """As :meth:`Entity.value`, a call shorter (a large file's hot path)."""
        self._read.add(name)
        text = self._attributes.get(name)
        if text is None:
            return None
        if "$" not in text and "\\" not in text:  # plain text: no location to find
            if len(text) > SHARED_LENGTH:
                return (Text(text),)
            shared = self.source.plain_values.get(text)
            if shared is None:
                shared = (Text(text),) if text else ()
                if len(self.source.plain_values) < SHARED_VALUES:
                    self.source.plain_values[text] = shared
            return shared
        return parse_value(text, self.attribute_location(name))

    def assert_fully_read(self) -> None:
        """As :meth:`Entity.assert_fully_read`, with the usual case (all read) in one call."""
        if not self._read.issuperset(self._attributes):
            super().assert_fully_read()

    def children(self) -> list[Entity]:
        """Child elements (comments and processing instructions skipped)."""
        if len(self.element) == 0:  # most elements: no lxml iteration
            return []
        return [
            XmlEntity(child, self.source) for child in self.element if isinstance(child.tag, str)
        ]


def read_root(entity: XmlEntity) -> str | None:
    """Check the root element (``<launch>``, no unknown attribute); its ``deprecated``."""
    if entity.tag != "launch":
        raise entity.error(
            f"the root element is <{entity.tag}>", expected="<launch> as the root element"
        )
    deprecated = entity.raw("deprecated")
    entity.assert_fully_read()
    return deprecated
