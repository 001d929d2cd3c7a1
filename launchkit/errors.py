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
"""

from __future__ import annotations

from dataclasses import dataclass


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
    ) -> None:
        super().__init__(message)
        self.message = message
        self.location = location
        self.expected = expected
        self.hint = hint

    def with_location(self, location: Location) -> LaunchkitError:
        """Attach ``location`` unless the error already knows a more precise one."""
        if self.location is None:
            self.location = location
        return self

    def format(self) -> str:
        """The user-facing text: ``FILE:LINE:COL: error: WHAT (expected ...)`` [+ hint]."""
        text = f"error: {self.message}"
        if self.expected:
            text += f" (expected {self.expected})"
        if self.location is not None:
            text = f"{self.location}: {text}"
        if self.hint:
            text += f"\n  hint: {self.hint}"
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
