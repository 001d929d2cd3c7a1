"""Hand-written tokenizer for attribute values: literal text and ``$(name arg ...)``.

The grammar is ROS 2 launch's (``launch/frontend/grammar.lark``):

* ``\\`` escapes the next character everywhere and is removed; ``$`` not followed by ``(`` is
  literal.
* ``$(NAME ARG ARG ...)``: NAME is a letter then letters, digits, ``_`` or ``-``; arguments are
  separated by exactly one space.
* An unquoted argument may not contain a space, a quote or a parenthesis (unless escaped); a
  single- or double-quoted one may, and may hold nested substitutions. Parts glue together:
  ``$(var $(var a)_x)``.
"""

from __future__ import annotations

import re

from launchkit.description.substitutions import SUBSTITUTIONS
from launchkit.description.substitutions.base import Substitution, Text, Value
from launchkit.errors import LaunchFileError, Location, did_you_mean

#: How deep ``$(...)`` may nest in one value (real files nest two or three levels).
MAX_DEPTH = 64


#: The characters that end a run of literal text at the top, in an unquoted argument, in a
#: quoted one: the parser jumps over everything else in one step (values are mostly text).
_TOP_SPECIAL = re.compile(r"[\\$]")
_ARGUMENT_SPECIAL = re.compile(r"[ )\\$'\"(]")
_QUOTED_SPECIAL = {"'": re.compile(r"['\\$]"), '"': re.compile(r'["\\$]')}


def parse_value(text: str, location: Location | None = None) -> Value:
    """Parse ``text`` into literal text and substitutions; ``location`` is where it starts."""
    if "$" not in text and "\\" not in text:
        return (Text(text),) if text else ()
    return _Parser(text, location).parse_top()


class _Parser:
    """Recursive-descent parser over one attribute value."""

    def __init__(self, text: str, location: Location | None) -> None:
        self.text = text
        self.pos = 0
        self.location = location
        self.depth = 0  # the ``$(`` open around the position

    # -- helpers -----------------------------------------------------------------------------

    def error(self, message: str, expected: str, at: int | None = None) -> LaunchFileError:
        where = self.location.shifted(self.pos if at is None else at) if self.location else None
        return LaunchFileError(message, where, expected=expected)

    def peek(self, offset: int = 0) -> str:
        index = self.pos + offset
        return self.text[index] if index < len(self.text) else ""

    def at_call(self) -> bool:
        return self.peek() == "$" and self.peek(1) == "("

    def skip_literal(self, special: re.Pattern[str], buffer: list[str]) -> None:
        """Move over literal text up to the next ``special`` character, into ``buffer``."""
        match = special.search(self.text, self.pos)
        end = match.start() if match else len(self.text)
        if end > self.pos:
            buffer.append(self.text[self.pos : end])
            self.pos = end

    # -- grammar -----------------------------------------------------------------------------

    def parse_top(self) -> Value:
        return tuple(self.parse_parts(_TOP_SPECIAL, "", ""))

    def parse_parts(self, special: re.Pattern[str], stops: str, name: str) -> list[Substitution]:
        """Literal text, ``\\`` escapes, nested ``$(...)`` and (in an argument) quoted parts,
        up to the text's end or a character of ``stops`` (not taken). ``special``: the
        characters that need a look here; ``name``: the substitution an argument is of."""
        parts: list[Substitution] = []
        buffer: list[str] = []
        while True:
            self.skip_literal(special, buffer)
            char = self.peek()
            if not char or char in stops:
                break
            if char == "\\" and self.pos + 1 < len(self.text):
                buffer.append(self.text[self.pos + 1])
                self.pos += 2
            elif self.at_call():
                _flush(buffer, parts)
                parts.append(self.parse_call())
            elif char in "'\"":  # only an argument stops at quotes (see _ARGUMENT_SPECIAL)
                _flush(buffer, parts)
                parts.extend(self.parse_quoted(char, name))
            elif char == "(":
                raise self.error(
                    f"unescaped '(' in an argument of $({name} ...)",
                    "a quoted argument or '\\(' for a literal parenthesis",
                )
            else:
                buffer.append(char)
                self.pos += 1
        _flush(buffer, parts)
        return parts

    def parse_call(self) -> Substitution:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.error(
                f"substitutions nested deeper than {MAX_DEPTH}",
                f"at most {MAX_DEPTH} levels of $(...) inside one another",
            )
        call = self._call()
        self.depth -= 1
        return call

    def _call(self) -> Substitution:
        start = self.pos
        self.pos += 2  # "$("
        name_start = self.pos
        if not self.peek().isalpha():
            raise self.error("malformed substitution", "a substitution name after '$('")
        while self.peek() and (self.peek().isalnum() or self.peek() in "_-"):
            self.pos += 1
        name = self.text[name_start : self.pos]
        args: list[Value] = []
        while True:
            char = self.peek()
            if char == ")":
                self.pos += 1
                break
            if char == "":
                raise self.error(
                    f"unterminated substitution $({name}", "')' to close it", at=len(self.text)
                )
            if char != " ":
                raise self.error(
                    f"unexpected {char!r} in $({name} ...)", "one space between arguments or ')'"
                )
            self.pos += 1
            if self.peek() in (" ", ")", ""):
                raise self.error(
                    f"extra space in $({name} ...)",
                    "exactly one space between arguments and none before ')'",
                )
            args.append(self.parse_argument(name))
        cls = SUBSTITUTIONS.get(name)
        where = self.location.shifted(start) if self.location else None
        if cls is None:
            raise LaunchFileError(
                f"unknown substitution $({name})",
                where,
                expected="one of: " + ", ".join(sorted(SUBSTITUTIONS)),
                hint=did_you_mean(name, SUBSTITUTIONS),
            )
        return cls(args, where)

    def parse_argument(self, name: str) -> Value:
        return tuple(self.parse_parts(_ARGUMENT_SPECIAL, " )", name))

    def parse_quoted(self, quote: str, name: str) -> list[Substitution]:
        start = self.pos
        self.pos += 1
        parts = self.parse_parts(_QUOTED_SPECIAL[quote], quote, name)
        if not self.peek():
            raise self.error(
                f"unterminated {quote} quote in $({name} ...)", f"a closing {quote}", at=start
            )
        self.pos += 1
        return parts or [Text("")]


def _flush(buffer: list[str], parts: list[Substitution]) -> None:
    if buffer:
        text = "".join(buffer)
        if parts and isinstance(parts[-1], Text):
            parts[-1] = Text(parts[-1].text + text)
        else:
            parts.append(Text(text))
        buffer.clear()
