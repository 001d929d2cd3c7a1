"""CMake's ``install(FILES|PROGRAMS|DIRECTORY ...)`` read into an :class:`InstallRule`.

The options understood are those that say what lands where: ``DESTINATION``, ``RENAME``,
``OPTIONAL``, ``FILES_MATCHING``, ``PATTERN glob [EXCLUDE]``, ``PERMISSIONS`` (only whether the
owner may execute), and those that change nothing here (``USE_SOURCE_PERMISSIONS``,
``COMPONENT``, ``EXCLUDE_FROM_ALL``, ``MESSAGE_NEVER``). Anything else (``REGEX``, ``TYPE``,
``install(TARGETS|SCRIPT|CODE|EXPORT ...)``) is a reason the package needs CMake.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import PurePosixPath

from launchkit.errors import Location

KINDS = ("FILES", "PROGRAMS", "DIRECTORY")
_WITH_VALUE = ("DESTINATION", "RENAME", "COMPONENT", "PATTERN")
_FLAGS = ("OPTIONAL", "USE_SOURCE_PERMISSIONS", "FILES_MATCHING", "EXCLUDE_FROM_ALL")
_FLAGS_TOO = ("MESSAGE_NEVER",)
_PERMISSION_LISTS = ("PERMISSIONS", "FILE_PERMISSIONS", "DIRECTORY_PERMISSIONS")
_PERMISSIONS = frozenset(
    f"{who}_{what}" for who in ("OWNER", "GROUP", "WORLD") for what in ("READ", "WRITE", "EXECUTE")
) | {"SETUID", "SETGID"}
_KEYWORDS = frozenset((*_WITH_VALUE, *_FLAGS, *_FLAGS_TOO, *_PERMISSION_LISTS, "REGEX", "TYPE"))


@dataclass(frozen=True)
class InstallRule:
    """One ``install()`` call: what (``kind``, ``sources`` as written, relative to the
    package or absolute) goes where (``destination``, relative to the install prefix)."""

    kind: str
    sources: tuple[str, ...]
    destination: str
    location: Location
    rename: str | None = None
    optional: bool = False
    executable: bool = False
    files_matching: bool = False
    patterns: tuple[tuple[str, bool], ...] = ()  # (glob, excluded)


def install_rule(location: Location, args: list[str]) -> InstallRule | str:
    """The rule ``install(ARGS)`` at ``location`` says, or why launchkit cannot follow it."""
    beyond = f"at {location}, which launchkit build does not run"
    kind = args[0] if args else ""
    if kind == "TARGETS":
        return f"it builds C++ (install(TARGETS ...) at {location})"
    if kind not in KINDS:
        return f"it uses install({kind} ...) {beyond}"
    position = 1
    sources: list[str] = []
    while position < len(args) and args[position] not in _KEYWORDS:
        sources.append(args[position])
        position += 1
    values: dict[str, str] = {}
    flags: set[str] = set()
    patterns: list[tuple[str, bool]] = []
    while position < len(args):
        word = args[position]
        position += 1
        if word in _WITH_VALUE:
            if position >= len(args):
                return f"install(... {word}) has no value {beyond}"
            value = args[position]
            position += 1
            if word == "PATTERN":
                excluded = position < len(args) and args[position] == "EXCLUDE"
                position += excluded
                patterns.append((value, excluded))
            else:
                values[word] = value
        elif word in _FLAGS or word in _FLAGS_TOO:
            flags.add(word)
        elif word in _PERMISSION_LISTS:
            while position < len(args) and args[position] in _PERMISSIONS:
                flags.add(args[position])
                position += 1
        else:
            return f"it uses install(... {word} ...) {beyond}"
    destination = values.get("DESTINATION")
    if destination is None:
        return f"install() without DESTINATION {beyond}"
    if os.path.isabs(destination) or ".." in PurePosixPath(destination).parts:
        return f"install() to '{destination}' outside the install prefix {beyond}"
    return InstallRule(
        kind=kind,
        sources=tuple(sources),
        destination=destination,
        location=location,
        rename=values.get("RENAME"),
        optional="OPTIONAL" in flags,
        executable=kind == "PROGRAMS" or "OWNER_EXECUTE" in flags,
        files_matching="FILES_MATCHING" in flags,
        patterns=tuple(patterns),
    )
