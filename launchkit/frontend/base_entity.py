"""What a tag parser sees of one element of a launch file, in any syntax.

A frontend (XML in ``frontend/xml``, YAML in ``frontend/yaml``) subclasses :class:`Entity` with
how its syntax stores a tag name, attributes, children and positions; the tag parsers in
``frontend/tags`` use only what is defined here, so one parser serves every syntax. Attributes are
read through :meth:`Entity.raw` (which marks them read), and :meth:`Entity.assert_fully_read`
then rejects any attribute no parser asked for, naming the ones it would have read, as ROS does.

XML attributes are always text. YAML values have types of their own, and ROS's YAML reader
checks them per attribute (a string where text is read, a float for ``period``, a boolean for
``scoped``): the parsers say which native type an attribute may also be given as (``native``),
and a syntax with types turns such a value into the text the parsers read (:meth:`typed_text`).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence

from launchkit.description.substitutions.base import Text, Value, literal
from launchkit.description.substitutions.grammar import parse_value
from launchkit.description.truth import BOOL_EXPECTED, bool_value
from launchkit.errors import LaunchFileError, Location, did_you_mean

_CHECKS = {
    "bool": BOOL_EXPECTED,
    "float": "a number",
    "int": "an integer",
    "ufloat": "a number >= 0",
}
#: The native type a typed syntax may give a checked attribute as.
_NATIVE = {"bool": "bool", "float": "float", "int": "int", "ufloat": "float"}


class Entity(ABC):
    """One element of a launch file: its tag, its attributes (parsed into values on first
    read, with locations for errors) and its child elements."""

    #: What errors call an attribute in this syntax.
    ATTRIBUTE = "attribute"
    #: Whether list values are text split by a sibling ``NAME-sep`` attribute (XML); a syntax
    #: with native lists (YAML) has no such attribute.
    SPLITS_LISTS = True

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

    # -- what a syntax may change --------------------------------------------------------------

    def label(self, tag: str | None = None) -> str:
        """How errors name tag ``tag`` (this entity's by default): ``<tag>`` in XML."""
        return f"<{tag or self.tag}>"

    def example(self, name: str) -> str:
        """How attribute ``name`` is written, for "expected" texts."""
        return f'{name}="..."'

    def key_location(self, name: str) -> Location:
        """Where attribute ``name`` is written (for an unknown attribute)."""
        return self.attribute_location(name)

    def typed_text(self, name: str, native: str) -> str | None:
        """Attribute ``name`` as text when it may also be given as a value of type ``native``
        (bool, float or int); a syntax whose values are all text just returns the text."""
        return self.attribute_text(name)

    def param_value(self, name: str, kind: str | None) -> tuple[Value, str | None] | None:
        """A ``<param>`` value and the type it is to be read as (``kind``: the ``type``
        attribute, None for YAML's rules), or None when absent. Text syntaxes read every value
        by ``kind``; a typed syntax may keep a value's own type."""
        value = self.value(name)
        return None if value is None else (value, kind)

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

    def raw(self, name: str, native: str | None = None) -> str | None:
        """Attribute text as written (marks it read); ``native``: the type (bool, float, int)
        a typed syntax may give it as instead of text."""
        self._read.add(name)
        if native is None:
            return self.attribute_text(name)
        return self.typed_text(name, native)

    def value(self, name: str, native: str | None = None) -> Value | None:
        """Attribute parsed into text and substitutions, or None when absent."""
        text = self.raw(name, native)
        if text is None:
            return None
        if "$" not in text and "\\" not in text:  # plain text: no location needed for errors
            return (Text(text),) if text else ()
        return parse_value(text, self.attribute_location(name))

    def required(self, name: str, what: str = "") -> Value:
        """A required attribute's value; an error naming the attribute when missing."""
        value = self.value(name)
        if value is None:
            expected = what or self.example(name)
            for written in self.attribute_names():
                hint = None if written in self._read else did_you_mean(written, [name])
                if hint:  # `exe:` for `exec:`: what the user wrote wrong, not a missing key
                    raise self._unknown(written, expected, hint)
            raise self.error(
                f"{self.label()} is missing {self.ATTRIBUTE} '{name}'", expected=expected
            )
        return value

    def plain(self, name: str, native: str | None = None) -> str | None:
        """Attribute that takes no substitutions (``\\`` escapes are removed)."""
        value = self.value(name, native)
        if value is None:
            return None
        text = literal(value)
        if text is None:
            raise self.error(
                f"{self.ATTRIBUTE} '{name}' of {self.label()} cannot contain substitutions",
                expected="plain text",
                attr=name,
            )
        return text

    def static_bool(self, name: str, default: bool) -> bool:
        """A boolean attribute that must be written literally."""
        text = self.plain(name, "bool")
        if text is None:
            return default
        value = bool_value(text)
        if value is None:
            raise self.error(
                f"{self.ATTRIBUTE} '{name}' of {self.label()} is {text!r}",
                expected=BOOL_EXPECTED,
                attr=name,
            )
        return value

    def checked(self, name: str, check: str, *, typed: bool = True) -> Value | None:
        """An attribute that may hold substitutions; when it is literal, its text is checked
        now (``check``: bool, float, int, ufloat) so a typo fails before anything starts.
        ``typed``: whether a typed syntax may give it as a value of that type (ROS reads a few
        such attributes, ``respawn`` for one, as text only)."""
        native = _NATIVE[check] if typed else None
        value = self.value(name, native)
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
                f"{self.ATTRIBUTE} '{name}' of {self.label()} is {text!r}",
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
                f"{self.ATTRIBUTE} '{name}' of {self.label()} is {text!r}",
                expected="one of " + ", ".join(choices),
                attr=name,
            )
        return value

    def assert_fully_read(self) -> None:
        """Reject attributes no parser asked for, naming the ones it would have read."""
        for name in self.attribute_names():
            if name not in self._read:
                allowed = sorted(self._read)
                expected = f"one of: {', '.join(allowed)}" if allowed else f"no {self.ATTRIBUTE}s"
                raise self._unknown(name, expected, did_you_mean(name, allowed))

    def _unknown(self, name: str, expected: str, hint: str | None) -> LaunchFileError:
        """The error for attribute ``name``, which no parser reads, located at its key."""
        return LaunchFileError(
            f"unknown {self.ATTRIBUTE} '{name}' on {self.label()}",
            self.key_location(name),
            expected=expected,
            hint=hint,
        )
