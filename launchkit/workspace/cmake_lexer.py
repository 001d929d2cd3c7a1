"""A ``CMakeLists.txt`` read into its command invocations (cmake-language(7)): each command's
name, its arguments (quoted, unquoted or bracket, as written) and its line and column.

Nothing is evaluated here; :mod:`launchkit.workspace.cmake_plan` expands variables and decides
what the commands mean.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from launchkit.errors import Location, UserError

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_BRACKET_OPEN = re.compile(r"\[(=*)\[")
_UNQUOTED_END = set(' \t\r\n()#"\\')


class CMakeSyntaxError(UserError):
    """A CMakeLists.txt that is not CMake (an unclosed parenthesis, quote or bracket)."""


@dataclass(frozen=True)
class Argument:
    """One argument as written: its text (escapes kept, variables not expanded) and whether
    it was ``"quoted"``, ``[[bracketed]]`` or unquoted."""

    text: str
    kind: str  # "quoted", "bracket" or "unquoted"


@dataclass(frozen=True)
class Command:
    """One command invocation: its name in lower case (CMake's are case-insensitive)."""

    name: str
    arguments: tuple[Argument, ...]
    location: Location


def read_commands(path: Path, shown: str) -> list[Command]:
    """The commands of the file at ``path``; errors name ``shown:line:col``."""
    return _Lexer(path.read_text(encoding="utf-8", errors="replace"), shown).commands()


class _Lexer:
    def __init__(self, text: str, shown: str) -> None:
        self.text = text
        self.shown = shown
        self.pos = 0

    def _location(self, pos: int) -> Location:
        line = self.text.count("\n", 0, pos) + 1
        col = pos - (self.text.rfind("\n", 0, pos) + 1) + 1
        return Location(self.shown, line, col)

    def _error(self, message: str, pos: int, expected: str) -> CMakeSyntaxError:
        return CMakeSyntaxError(message, self._location(pos), expected=expected)

    def commands(self) -> list[Command]:
        found: list[Command] = []
        while True:
            self._skip_space_and_comments()
            if self.pos >= len(self.text):
                return found
            start = self.pos
            match = _NAME.match(self.text, self.pos)
            if match is None:
                raise self._error(
                    f"unexpected {self.text[self.pos]!r}", start, "a command such as project(...)"
                )
            self.pos = match.end()
            while self.pos < len(self.text) and self.text[self.pos] in " \t":
                self.pos += 1
            if not self.text.startswith("(", self.pos):
                raise self._error(f"'{match.group()}' is not followed by '('", start, "name(...)")
            self.pos += 1
            arguments = self._arguments(start)
            found.append(Command(match.group().lower(), tuple(arguments), self._location(start)))

    def _skip_space_and_comments(self) -> None:
        while self.pos < len(self.text):
            char = self.text[self.pos]
            if char in " \t\r\n":
                self.pos += 1
            elif char == "#":
                self._comment()
            else:
                return

    def _comment(self) -> None:
        bracket = _BRACKET_OPEN.match(self.text, self.pos + 1)
        if bracket is not None:
            self.pos = bracket.start()
            self._bracket(self.pos)  # a bracket comment: the same syntax as a bracket argument
            return
        end = self.text.find("\n", self.pos)
        self.pos = len(self.text) if end < 0 else end

    def _arguments(self, start: int) -> list[Argument]:
        arguments: list[Argument] = []
        depth = 0  # nested parentheses (in conditions) become arguments of their own
        while True:
            self._skip_space_and_comments()
            if self.pos >= len(self.text):
                raise self._error("unclosed '('", start, "a ')' closing the command")
            char = self.text[self.pos]
            if char == ")":
                self.pos += 1
                if depth == 0:
                    return arguments
                depth -= 1
                arguments.append(Argument(")", "unquoted"))
            elif char == "(":
                self.pos += 1
                depth += 1
                arguments.append(Argument("(", "unquoted"))
            elif char == '"':
                arguments.append(Argument(self._quoted(), "quoted"))
            elif _BRACKET_OPEN.match(self.text, self.pos):
                arguments.append(Argument(self._bracket(self.pos), "bracket"))
            else:
                arguments.append(Argument(self._unquoted(), "unquoted"))

    def _quoted(self) -> str:
        start = self.pos
        self.pos += 1
        while self.pos < len(self.text):
            char = self.text[self.pos]
            if char == "\\":
                self.pos += 2
            elif char == '"':
                self.pos += 1
                return self.text[start + 1 : self.pos - 1]
            else:
                self.pos += 1
        raise self._error("unclosed quoted argument", start, 'a closing "')

    def _bracket(self, start: int) -> str:
        match = _BRACKET_OPEN.match(self.text, start)
        assert match is not None
        close = "]" + match.group(1) + "]"
        end = self.text.find(close, match.end())
        if end < 0:
            raise self._error("unclosed bracket", start, f"a closing {close}")
        self.pos = end + len(close)
        body = self.text[match.end() : end]
        return body[1:] if body.startswith("\n") else body  # a first newline is dropped

    def _unquoted(self) -> str:
        start = self.pos
        while self.pos < len(self.text):
            char = self.text[self.pos]
            if char == "\\":
                self.pos += 2
            elif char in _UNQUOTED_END:
                break
            else:
                self.pos += 1
        return self.text[start : self.pos]
