"""A large YAML launch file's ``launch:`` list read without PyYAML's events, when it can be.

:func:`launchkit.safe_yaml.list_items` builds its nodes from PyYAML's events, about 35 us per
line of a ``- let: {...}`` file: 7 s for a 50 MB one. Most large files are written in a small
part of YAML: block mappings and lists, one-line flow collections of plain scalars, one-line
scalars. This module reads that part line by line with ``re`` and builds the very nodes the
composer builds (kind, value, tag, style, text, line, column, size), typing plain scalars with
the same resolver. Anything else (tabs, anchors, tags, block or multi-line scalars, a character
PyYAML refuses, a ``: `` or ``#`` inside a scalar, an empty value, deep nesting, a number too
long, ...) makes it give up: PyYAML's composer then reads the file from its start, the items
already given are composed again and dropped, and the rest (errors included) is the
composer's. So the reader never raises an error of its own, and giving up costs only time.
Texts under :data:`THRESHOLD` go to the composer directly: small files see no change at all.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from pathlib import Path

from launchkit import safe_yaml
from launchkit.safe_yaml import Node
from launchkit.safe_yaml_fast.line_item import LineItem
from launchkit.safe_yaml_fast.lines import LineReader
from launchkit.safe_yaml_fast.scalars import GiveUp

__all__ = ["THRESHOLD", "LineItem", "list_items"]

#: Texts shorter than this (in characters) are composed by PyYAML alone.
THRESHOLD = 256 * 1024


def list_items(text: str, path: Path, key: str) -> Iterator[Node | LineItem]:
    """What :func:`launchkit.safe_yaml.list_items` gives (the same nodes, errors and
    :class:`~launchkit.safe_yaml.NotAList`), read line by line where the text allows; an item
    written on one line comes as a :class:`LineItem`, whose :meth:`~LineItem.node` is the
    composer's node."""
    if len(text) < THRESHOLD:
        yield from safe_yaml.list_items(text, path, key)
        return
    reader = LineReader(text, str(path))
    try:
        yield from reader.items(key)
        return
    except GiveUp:
        given = reader.given
    del reader  # its lines: the composer reads the text itself
    composed = safe_yaml.list_items(text, path, key)
    for _ in itertools.islice(composed, given):  # the same items again: errors stay in order
        pass
    yield from composed
