"""What a tag parser sees of one element of a launch file, in any syntax.

A frontend (XML in ``frontend/xml``, YAML next) subclasses :class:`Entity` with how its syntax
stores a tag name, attributes, children and positions; the tag parsers in ``frontend/tags`` use
only what is defined here, so one parser serves every syntax. Attributes are read through
:meth:`Entity.raw` (which marks them read), and :meth:`Entity.assert_fully_read` then rejects
any attribute no parser asked for, naming the ones it would have read, as ROS does.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence

from launchkit.description.substitutions.base import Value, literal
from launchkit.description.substitutions.grammar import parse_value
from launchkit.description.truth import BOOL_EXPECTED, bool_value
from launchkit.errors import LaunchFileError, Location

_CHECKS = {
    "bool": BOOL_EXPECTED,
    "float": "a number",
    "int": "an integer",
    "ufloat": "a number >= 0",
}


class Entity(ABC):
    """One element of a launch file: its tag, its attributes (parsed into values on first
    read, with locations for errors) and its child elements."""

    def __init__(self, tag: str) -> None:
        self.tag = tag
        self._read: set[str] = set()

    # -- what a syntax provides ----------------------------------------------------------------

    @property
    @abstractmethod
    def location(self) -> Location:
        """Where the element begins."""

    @abstractmethod
    def attribute_location(self, name: str) -> Location:
        """Where attribute ``name``'s value begins (the element's location if it is absent)."""

    @abstractmethod
    def attribute_names(self) -> list[str]:
        """The names of the attributes as written, in order."""

    @abstractmethod
    def attribute_text(self, name: str) -> str | None:
        """Attribute ``name`` as text, or None when absent (does not mark it read)."""

    @abstractmethod
    def children(self) -> list[Entity]:
        """The child elements, in order."""

    # -- reading attributes (the same for every syntax) ----------------------------------------

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

    def has(self, name: str) -> bool:
        """Whether attribute ``name`` is present."""
        return self.attribute_text(name) is not None

    def raw(self, name: str) -> str | None:
        """Attribute text as written (marks it read)."""
        self._read.add(name)
        return self.attribute_text(name)

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
        now (``check``: bool, float, int, ufloat) so a typo fails before anything starts."""
        value = self.value(name)
        text = None if value is None else literal(value)
        if text is None:
            return value
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
                f"attribute '{name}' of <{self.tag}> is {text!r}",
                expected=_CHECKS[check],
                attr=name,
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

    def assert_fully_read(self) -> None:
        """Reject attributes no parser asked for, naming the ones it would have read."""
        for name in self.attribute_names():
            if name not in self._read:
                allowed = sorted(self._read)
                expected = ", ".join(allowed) if allowed else "no attributes"
                raise self.error(
                    f"unknown attribute '{name}' on <{self.tag}>",
                    expected=f"one of: {expected}" if allowed else expected,
                    attr=name,
                )
