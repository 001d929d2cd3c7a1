"""One XML element as the tag parsers see it: typed attribute access with locations, and a
check that no attribute or child was left unread."""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from launchkit.description.substitutions.base import Value, literal
from launchkit.description.substitutions.grammar import parse_value
from launchkit.description.truth import BOOL_EXPECTED, bool_value
from launchkit.errors import LaunchFileError, Location


@dataclass
class SourceFile:
    """A launch file's path and text (for columns in error messages)."""

    path: Path
    text: str
    _line_starts: list[int] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._line_starts = [0] + [m.end() for m in re.finditer("\n", self.text)]

    def offset(self, line: int) -> int:
        """Character offset where 1-based ``line`` starts."""
        return self._line_starts[min(max(line, 1), len(self._line_starts)) - 1]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of a character offset."""
        line = 0
        low, high = 0, len(self._line_starts) - 1
        while low <= high:
            mid = (low + high) // 2
            if self._line_starts[mid] <= offset:
                line, low = mid, mid + 1
            else:
                high = mid - 1
        return line + 1, offset - self._line_starts[line] + 1

    def location(self, offset: int) -> Location:
        """The location of a character offset."""
        line, col = self.position(offset)
        return Location(str(self.path), line, col)


class Entity:
    """An element of a launch file; attributes are parsed into values on first read."""

    def __init__(self, element: etree._Element, source: SourceFile) -> None:
        self.element = element
        self.source = source
        self.tag = str(element.tag)
        self._read: set[str] = set()
        self._start = self._find_start()

    # -- locations ---------------------------------------------------------------------------

    def _find_start(self) -> int:
        sourceline: int | None = self.element.sourceline  # type: ignore[assignment]
        line = sourceline or 1
        # lxml reports the line where the start tag ends; search back a little for "<tag".
        search_from = self.source.offset(max(1, line - 20))
        search_to = self.source.offset(line + 1) if line < len(self.source._line_starts) else None
        window = self.source.text[search_from:search_to]
        matches = list(re.finditer(r"<" + re.escape(self.tag) + r"(?=[\s/>])", window))
        return search_from + matches[-1].start() if matches else self.source.offset(line)

    @property
    def location(self) -> Location:
        """Where the element's start tag begins."""
        return self.source.location(self._start)

    def attribute_location(self, name: str) -> Location:
        """Where attribute ``name``'s value begins (after the quote)."""
        pattern = re.compile(r"\s" + re.escape(name) + r"\s*=\s*([\"'])")
        match = pattern.search(self.source.text, self._start)
        if match is None:
            return self.location
        return self.source.location(match.end())

    def error(
        self,
        message: str,
        *,
        expected: str | None = None,
        attr: str | None = None,
        hint: str | None = None,
    ) -> LaunchFileError:
        """A parse error located at this element or one of its attributes."""
        where = self.attribute_location(attr) if attr else self.location
        return LaunchFileError(message, where, expected=expected, hint=hint)

    # -- attributes --------------------------------------------------------------------------

    def has(self, name: str) -> bool:
        """Whether attribute ``name`` is present."""
        return name in self.element.attrib

    def raw(self, name: str) -> str | None:
        """Attribute text as written (marks it read)."""
        self._read.add(name)
        value = self.element.get(name)
        return None if value is None else str(value)

    def value(self, name: str) -> Value | None:
        """Attribute parsed into text and substitutions, or None when absent."""
        text = self.raw(name)
        if text is None:
            return None
        return parse_value(text, self.attribute_location(name))

    def required(self, name: str, what: str = "") -> Value:
        """A required attribute's value; an error naming the attribute when missing."""
        value = self.value(name)
        if value is None:
            raise self.error(
                f"<{self.tag}> is missing attribute '{name}'",
                expected=what or f'{name}="..."',
            )
        return value

    def plain(self, name: str) -> str | None:
        """Attribute that takes no substitutions (``\\`` escapes are removed)."""
        value = self.value(name)
        if value is None:
            return None
        text = literal(value)
        if text is None:
            raise self.error(
                f"attribute '{name}' of <{self.tag}> cannot contain substitutions",
                expected="plain text",
                attr=name,
            )
        return text

    def static_bool(self, name: str, default: bool) -> bool:
        """A boolean attribute that must be written literally."""
        text = self.plain(name)
        if text is None:
            return default
        value = bool_value(text)
        if value is None:
            raise self.error(
                f"attribute '{name}' of <{self.tag}> is {text!r}", expected=BOOL_EXPECTED, attr=name
            )
        return value

    def checked(self, name: str, check: str) -> Value | None:
        """An attribute that may hold substitutions; when it is literal, its text is checked
        now (``check``: bool, float, int, uint) so a typo fails before anything starts."""
        value = self.value(name)
        text = None if value is None else literal(value)
        if text is None:
            return value
        expected = {
            "bool": BOOL_EXPECTED,
            "float": "a number",
            "int": "an integer",
            "ufloat": "a number >= 0",
        }[check]
        ok = True
        if check == "bool":
            ok = bool_value(text) is not None
        else:
            try:
                number = float(text) if check != "int" else int(text)
                ok = check != "ufloat" or number >= 0
            except ValueError:
                ok = False
        if not ok:
            raise self.error(
                f"attribute '{name}' of <{self.tag}> is {text!r}", expected=expected, attr=name
            )
        return value

    def choice(self, name: str, choices: Sequence[str]) -> Value | None:
        """An attribute whose literal text must be one of ``choices``."""
        value = self.value(name)
        text = None if value is None else literal(value)
        if text is not None and text not in choices:
            raise self.error(
                f"attribute '{name}' of <{self.tag}> is {text!r}",
                expected="one of " + ", ".join(choices),
                attr=name,
            )
        return value

    # -- children ----------------------------------------------------------------------------

    def children(self) -> list[Entity]:
        """Child elements (comments and processing instructions skipped)."""
        return [Entity(child, self.source) for child in self.element if isinstance(child.tag, str)]

    def assert_fully_read(self) -> None:
        """Reject attributes no parser asked for, naming the ones it would have read."""
        for raw_name in self.element.attrib:
            name = raw_name if isinstance(raw_name, str) else raw_name.decode()
            if name not in self._read:
                allowed = sorted(self._read)
                expected = ", ".join(allowed) if allowed else "no attributes"
                raise self.error(
                    f"unknown attribute '{name}' on <{self.tag}>",
                    expected=f"one of: {expected}" if allowed else expected,
                    attr=name,
                )
