"""One XML element as the tag parsers see it: attributes with the line and column they were
written at (expat or lxml gives the line; the column is found in the source text)."""

from __future__ import annotations

import bisect
import functools
import re
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.errors import Location
from launchkit.frontend.base_entity import Entity

if TYPE_CHECKING:
    from lxml import etree

    from launchkit.frontend.xml.expat_tree import Element

    #: An element as expat (a plain file) or lxml (any other) read it.
    AnyElement = Element | etree._Element


@functools.lru_cache(maxsize=256)
def _attribute_pattern(name: str) -> re.Pattern[str]:
    """Finds ``NAME = "`` in a start tag."""
    return re.compile(r"\s" + re.escape(name) + r"\s*=\s*([\"'])")


class SourceFile:
    """A launch file's path and text (for columns in error messages)."""

    def __init__(self, path: Path, text: str) -> None:
        self.path = path
        self.text = text
        self._line_starts = [0] + [m.end() for m in re.finditer("\n", text)]

    def offset(self, line: int) -> int:
        """Character offset where 1-based ``line`` starts."""
        return self._line_starts[min(max(line, 1), len(self._line_starts)) - 1]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of a character offset."""
        line = max(bisect.bisect_right(self._line_starts, offset) - 1, 0)
        return line + 1, offset - self._line_starts[line] + 1

    def location(self, offset: int) -> Location:
        """The location of a character offset."""
        line, col = self.position(offset)
        return Location(str(self.path), line, col)


class XmlEntity(Entity):
    """An element of an XML launch file."""

    def __init__(self, element: AnyElement, source: SourceFile) -> None:
        super().__init__(str(element.tag))
        self.element = element
        self.source = source
        self._start = self._find_start()
        self._location: Location | None = None

    def _find_start(self) -> int:
        sourceline: int | None = self.element.sourceline  # type: ignore[assignment]
        line = sourceline or 1
        # lxml reports the line where the start tag ends (expat where it begins); search back
        # a little for "<tag".
        text = self.source.text
        search_from = self.source.offset(max(1, line - 20))
        end = self.source.offset(line + 1) if line < len(self.source._line_starts) else len(text)
        opening = "<" + self.tag
        while True:
            found = text.rfind(opening, search_from, end)
            if found < 0:
                return self.source.offset(line)
            following = text[found + len(opening) : found + len(opening) + 1]
            if following.isspace() or following in ("/", ">"):
                return found
            end = found

    @property
    def location(self) -> Location:
        """Where the element's start tag begins."""
        if self._location is None:
            self._location = self.source.location(self._start)
        return self._location

    def attribute_location(self, name: str) -> Location:
        """Where attribute ``name``'s value begins (after the quote)."""
        match = _attribute_pattern(name).search(self.source.text, self._start)
        if match is None:
            return self.location
        return self.source.location(match.end())

    def attribute_names(self) -> list[str]:
        """The element's attribute names."""
        return [n if isinstance(n, str) else n.decode() for n in self.element.keys()]

    def attribute_text(self, name: str) -> str | None:
        """The attribute's text as lxml read it (entities and character references resolved)."""
        value = self.element.get(name)
        return None if value is None else str(value)

    def children(self) -> list[Entity]:
        """Child elements (comments and processing instructions skipped)."""
        if len(self.element) == 0:  # most elements: no lxml iteration
            return []
        return [
            XmlEntity(child, self.source) for child in self.element if isinstance(child.tag, str)
        ]
