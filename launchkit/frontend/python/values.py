"""Turning what Python launch files pass around (str, substitutions, lists of both) into
launchkit values, and finding the line of the launch file that built an action."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from launchkit.description.substitutions.base import Substitution, Text, Value
from launchkit.errors import LaunchFileError, Location

#: The file being loaded; actions built while it runs get locations in it.
_loading: list[Path] = []


class SubstitutionLike:
    """Base of the stand-in substitution classes: each wraps one launchkit substitution."""

    def __init__(self, inner: Substitution) -> None:
        self.inner = inner

    def __add__(self, other: object) -> list[object]:
        return [self, other]

    def __radd__(self, other: object) -> list[object]:
        return [other, self]


def to_value(item: Any) -> Value:
    """A str, a stand-in substitution, or a (nested) list of them, as one launchkit value."""
    if item is None:
        return ()
    if isinstance(item, str):
        return (Text(item),)
    if isinstance(item, SubstitutionLike):
        return (item.inner,)
    if isinstance(item, Path):
        return (Text(str(item)),)
    if isinstance(item, int | float | bool):
        return (Text(str(item).lower() if isinstance(item, bool) else str(item)),)
    if isinstance(item, Iterable):
        parts: list[Substitution] = []
        for element in item:
            parts.extend(to_value(element))
        return tuple(parts)
    raise LaunchFileError(
        f"cannot use a {type(item).__name__} as text in a launch file",
        here(),
        expected="a str, a substitution or a list of them",
    )


def optional_value(item: Any) -> Value | None:
    """Like :func:`to_value`, keeping None as "not given"."""
    return None if item is None else to_value(item)


def here() -> Location | None:
    """Where in the file being loaded the current call comes from."""
    if not _loading:
        return None
    target = str(_loading[-1])
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_filename == target:
            return Location(target, frame.f_lineno)
        frame = frame.f_back  # type: ignore[assignment]
    return Location(target)


def unsupported(name: str) -> type:
    """A stand-in for a part of the API launchkit does not implement: using it is an error."""

    def refuse(*_args: object, **_kwargs: object) -> None:
        raise LaunchFileError(
            f"{name} is not supported in Python launch files run by launchkit",
            here(),
            expected="the declarative launch API (actions, substitutions, conditions)",
            hint="write this part as an XML launch file, or use a plain action",
        )

    return type(name, (), {"__init__": refuse})


def argv_text(items: Any) -> tuple[Any, ...]:
    """A command given as a list of words, as one command-line value (each word quoted)."""
    if isinstance(items, str | SubstitutionLike):
        return to_value(items)
    parts: list[Any] = []
    for index, item in enumerate(items):
        parts.extend([" " if index else "", "'", item, "'"])
    return to_value(parts)
