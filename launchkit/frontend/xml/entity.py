"""One XML element as the tag parsers see it: attributes with the line and column they were
written at (lxml gives the line; the column is found in the source text)."""

from __future__ import annotations

import bisect
import re
from pathlib import Path

from lxml import etree

from launchkit.errors import Location
from launchkit.frontend.base_entity import Entity

#: How many lines before the line lxml gives an element's start tag may begin (a start tag
#: written over several lines).
LINES_BACK = 20


class SourceFile:
    """A launch file's path and text, for the columns of locations."""

    def __init__(self, path: Path, text: str) -> None:
        self.path = path
        self.file = str(path)
        self.text = text
        #: Where each line starts (offsets into ``text``).
        self.line_starts = [0] + [match.end() for match in re.finditer("\n", text)]

    def offset(self, line: int) -> int:
        """Offset where 1-based ``line`` starts (clamped to the file)."""
        return self.line_starts[min(max(line, 1), len(self.line_starts)) - 1]

    def line_end(self, line: int) -> int:
        """Offset where 1-based ``line`` ends (the next one starts, or the text ends)."""
        return self.offset(line + 1) if line < len(self.line_starts) else len(self.text)

    def location(self, offset: int) -> Location:
        """The 1-based line and column of an offset."""
        index = max(bisect.bisect_right(self.line_starts, offset) - 1, 0)
        return Location(self.file, index + 1, offset - self.line_starts[index] + 1)


class XmlEntity(Entity):
    """An element of an XML launch file."""

    def __init__(self, element: etree._Element, source: SourceFile) -> None:
        super().__init__(str(element.tag))
        self.element = element
        self.source = source
        self._attributes: dict[str, str] = dict(element.items())  # type: ignore[arg-type]
        self._start = self._find_start()

    def _find_start(self) -> int:
        """The offset of the ``<tag`` that starts the element: on the line lxml gives (where
        the start tag ends), or a few lines before it."""
        sourceline: int | None = self.element.sourceline  # type: ignore[assignment]
        line = sourceline or 1
        text = self.source.text
        search_from = self.source.offset(line - LINES_BACK)
        end = self.source.line_end(line)
        opening = "<" + self.tag
        while True:
            found = text.rfind(opening, search_from, end)
            if found < 0:
                return self.source.offset(line)
            following = text[found + len(opening) : found + len(opening) + 1]
            if not following or following.isspace() or following in "/>":
                return found
            end = found  # "<tagname" is another tag

    @property
    def location(self) -> Location:
        """Where the element's start tag begins."""
        return self.source.location(self._start)

    def attribute_location(self, name: str) -> Location:
        """Where attribute ``name``'s value begins (after the quote)."""
        pattern = re.compile(r"\s" + re.escape(name) + r"\s*=\s*[\"']")
        match = pattern.search(self.source.text, self._start)
        if match is None:
            return self.location
        return self.source.location(match.end())

    def attribute_names(self) -> list[str]:
        """The element's attribute names."""
        return list(self._attributes)

    def attribute_text(self, name: str) -> str | None:
        """The attribute's text as lxml read it (entities and character references resolved)."""
        return self._attributes.get(name)

    def children(self) -> list[Entity]:
        """Child elements (entity references, with no tag name, skipped)."""
        return [
            XmlEntity(child, self.source) for child in self.element if isinstance(child.tag, str)
        ]
