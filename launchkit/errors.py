"""Every error launchkit reports to a user, in one tree.

::

    LaunchkitError                 anything launchkit reports without a traceback
    ├── UserError                  the user's input is wrong; exit status 2
    │   ├── LaunchFileError        a launch file is malformed or fails a check (has a location)
    │   ├── LaunchArgumentError    a ``name:=value`` item, a missing required arg, a bad choice
    │   └── PackageNotFoundError   an unknown package or executable (lists where it looked)
    └── RuntimeLaunchError         something failed while running (a ``$(command)``, a spawn)

Each error carries an optional :class:`Location`; :meth:`LaunchkitError.format` renders the
one-line ``FILE:LINE:COL: error: WHAT (expected ...)`` form, plus a hint line when there is one.
An error inside an included file also carries the ``<include>`` locations that led to it,
outermost first: ``a.launch.xml:12:3 -> b.launch.py:40: error: ...``.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from dataclasses import dataclass

_NAMED_CONTROLS = {"\n": "\\n", "\r": "\\r", "\0": "\\0"}
#: Control characters (C0 but tab, DEL, C1) as escapes: a name or a file must not be able to
#: move the cursor, clear the screen or forge a line in launchkit's own messages.
_ESCAPES = {
    code: _NAMED_CONTROLS.get(chr(code), f"\\x{code:02x}")
    for code in [*range(0x20), *range(0x7F, 0xA0)]
    if code != 0x09
}


def printable(text: str) -> str:
    """``text`` with its control characters escaped (``\\x1b``, ``\\r``, ``\\n``), tabs kept."""
    return text.translate(_ESCAPES)


def did_you_mean(name: str, choices: Iterable[str]) -> str | None:
    """A hint naming the one of ``choices`` that ``name`` looks like a typo of (``exe`` for
    ``exec``), or None when none is close: for unknown tags, attributes and substitutions."""
    close = difflib.get_close_matches(name, list(choices), n=1)
    return f"did you mean '{close[0]}'?" if close else None


@dataclass(frozen=True)
class Location:
    """Where in a launch file something is: 1-based line and column (0 when unknown)."""

    file: str
    line: int = 0
    col: int = 0

    def __str__(self) -> str:
        if self.line and self.col:
            return f"{self.file}:{self.line}:{self.col}"
        if self.line:
            return f"{self.file}:{self.line}"
        return self.file

    def shifted(self, offset: int) -> Location:
        """This location moved ``offset`` columns to the right (for text inside an attribute)."""
        if not self.line or not self.col:
            return self
        return Location(self.file, self.line, self.col + offset)


class LaunchkitError(Exception):
    """Base of every error launchkit reports as one readable message."""

    exit_status = 1

    def __init__(
        self,
        message: str,
        location: Location | None = None,
        *,
        expected: str | None = None,
        hint: str | None = None,
        quoted: list[str] | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.location = location
        self.expected = expected
        self.hint = hint
        self.quoted = quoted or []  # lines quoted under the message (a program's last words)
        self.include_chain: list[Location] = []  # the <include>s that led to the location

    def with_location(self, location: Location) -> LaunchkitError:
        """Attach ``location`` unless the error already knows a more precise one."""
        if self.location is None:
            self.location = location
        return self

    def included_from(self, include: Location) -> LaunchkitError:
        """Record that the error happened in a file included at ``include`` (call from the
        innermost include outwards). An error located at the include itself gets no link."""
        if include != self.location and include not in self.include_chain:
            self.include_chain.insert(0, include)
        return self

    def format(self) -> str:
        """The user-facing text: ``[INCLUDE -> ...] FILE:LINE:COL: error: WHAT (expected ...)``
        [+ quoted lines] [+ hint]."""
        text = f"error: {self.message}"
        if self.expected:
            text += f" (expected {self.expected})"
        if self.location is not None:
            where = " -> ".join(str(place) for place in [*self.include_chain, self.location])
            text = f"{where}: {text}"
        text = printable(text)
        for line in self.quoted:
            text += f"\n  | {printable(line)}"
        if self.hint:
            text += f"\n  hint: {printable(self.hint)}"
        return text

    def __str__(self) -> str:
        return self.format()


class UserError(LaunchkitError):
    """The user's input is wrong; reported before anything starts, exit status 2."""

    exit_status = 2


class LaunchFileError(UserError):
    """A launch file is malformed or fails a static check."""


class LaunchArgumentError(UserError):
    """A bad ``name:=value`` item, a missing required argument or a choice violation."""


class PackageNotFoundError(UserError):
    """A package, executable or launch file could not be found in the package index."""


class RuntimeLaunchError(LaunchkitError):
    """Something failed while the launch was running (it is then shut down cleanly)."""
