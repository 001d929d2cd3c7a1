"""The scalars and one-line flow collections of :mod:`launchkit.safe_yaml_fast`'s subset of
YAML, and what it gives up on: typed and located as :mod:`launchkit.safe_yaml` does."""

from __future__ import annotations

import re
from typing import Any

import yaml

from launchkit import safe_yaml
from launchkit.safe_yaml import Node

#: How deep this reader follows mappings and lists before it gives up (far under
#: :data:`launchkit.safe_yaml.MAX_DEPTH`, whose error is then the composer's).
MAX_DEPTH = 30
#: Keys longer than this, spaces before the colon included, are left to PyYAML (libyaml refuses
#: a block key whose colon is over 1024 characters after its start).
MAX_KEY_LENGTH = 1000

STR = "tag:yaml.org,2002:str"
_MERGE = "tag:yaml.org,2002:merge"
_LOADER = safe_yaml._Loader
_RESOLVED_BY_FIRST = frozenset(_LOADER.yaml_implicit_resolvers)
_RESOLVES_ANY = None in _RESOLVED_BY_FIRST
#: The style PyYAML's parser gives a plain scalar ('' from libyaml, None from pure Python).
_PLAIN_STYLE = next(e.style for e in yaml.parse("a", Loader=_LOADER) if type(e) is yaml.ScalarEvent)
#: A character PyYAML's reader refuses, a tab or a carriage return, a line break of YAML's
#: own (NEL, LS, PS) or a byte-order mark: the reader stops at the line holding the first.
_BAD = re.compile(
    "[^\n\x20-\x7e\xa0-\u2027\u202a-\ud7ff\ue000-\ufefe\uff00-\ufffd\U00010000-\U0010ffff]"
)
#: Plain scalars: a first character no indicator, a ``-`` only before a digit or ``.``; then
#: letters, digits and a few safe signs (no ``:``, ``#`` or brackets; no ``,`` or quotes in
#: flow collections, where they are split, not scanned).
_FIRST = r"(?:[\w./~$(+]|-[0-9.])"
PLAIN = re.compile(_FIRST + r"[\w./~$()+=@ ,;'\"\-]*")
_FLOW_PLAIN = re.compile(_FIRST + r"[\w./~$()+=@ ;\-]*")
#: A block mapping's key: a plain scalar of the same characters.
KEY = re.compile(_FIRST + r"[\w./~$()+=@ ,;\-]*")
_FIRST_CHARS = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./~$(+")
#: First characters of plain scalars that are text whatever follows (no resolver starts so).
TEXT_FIRST = frozenset(() if _RESOLVES_ANY else _FIRST_CHARS - _RESOLVED_BY_FIRST)
_ASCII_OK = bytes([10, *range(0x20, 0x7F)])
_DIGITS_DOT = frozenset("0123456789.")
QUOTED = re.compile(r"'[^']*'|\"[^\"\\]*\"")
_SPACES = re.compile(r"[ ]*")


def first_bad(text: str) -> int | None:
    """Where the first character :data:`_BAD` finds is (None: nowhere); ASCII text is
    checked by ``bytes.translate``, many times faster than a regular expression."""
    if text.isascii() and not text.encode("ascii").translate(None, _ASCII_OK):
        return None
    found = _BAD.search(text)
    return None if found is None else found.start()


def split_key(text: str) -> tuple[str, str | None, int] | None:
    """``key: value`` as the key, the value and the value's offset; ``key:`` as the key and
    None; None for anything else (a key must be a plain scalar)."""
    name, colon, rest = text.partition(": ")
    if colon:
        value = rest.lstrip(" ")
        offset = len(name) + 2 + len(rest) - len(value)
    elif text.endswith(":"):
        name, value, offset = text[:-1], None, 0
    else:
        return None
    key = name.rstrip(" ")
    if len(name) > MAX_KEY_LENGTH or not KEY.fullmatch(key):
        return None
    return key, value, offset


def _starts_plain(text: str) -> bool:
    """Whether a plain scalar may begin so (no indicator; ``-`` only before a digit or ``.``)."""
    first = text[:1]
    if first in _FIRST_CHARS:
        return True
    return first == "-" and text[1:2] in _DIGITS_DOT and len(text) > 1


def _simple(text: str, start: int, end: int, is_map: bool) -> bool:
    """Whether ``text[start:end]``, inside a flow collection's brackets, holds plain scalars
    only (what else may be in them is checked as it is split)."""
    for sign in "{}[]'\"" if is_map else "{}[]'\":":
        if text.find(sign, start, end) >= 0:
            return False
    return True


class GiveUp(Exception):
    """The text leaves the part of YAML this reader follows."""


#: One ``key: value`` pair of plain scalars on a line: the key as written, its 1-based column,
#: its tag and value; then the same of the value.
Cell = tuple[str, int, str, Any, str, int, str, Any]


def plain_scalar(file: str, line: int, col: int, text: str, tag: str, value: Any) -> Node:
    """The node of a plain scalar written ``text`` and typed ``tag`` and ``value``."""
    return Node("scalar", file, line, col, value, _PLAIN_STYLE, tag, text)


def cell_pairs(cells: list[Cell], file: str, line: int) -> list[tuple[Node, Node]]:
    """The key and value nodes of ``cells`` (of ``line`` of ``file``)."""
    return [
        (
            Node("scalar", file, line, key_col, key_value, _PLAIN_STYLE, key_tag, key),
            Node("scalar", file, line, col, value, _PLAIN_STYLE, tag, text),
        )
        for key, key_col, key_tag, key_value, text, col, tag, value in cells
    ]


class FlowReader:
    """Scalars and flow collections to nodes, for the lines of ``file``."""

    def __init__(self, file: str) -> None:
        self.file = file
        self.types: dict[str, tuple[str, Any]] = {}  # plain scalars typed, by their text
        self.loader: Any = None

    def flow(self, text: str, at: int, row: int, col: int, depth: int) -> tuple[Node, int]:
        """The flow collection opening at ``text[at]`` and where it ends in ``text``."""
        if depth > MAX_DEPTH:
            raise GiveUp
        is_map = text[at] == "{"
        node = Node("map" if is_map else "seq", self.file, row + 1, col + at + 1)
        close = "}" if is_map else "]"
        end = text.find(close, at)
        if end > 0 and _simple(text, at + 1, end, is_map):
            if is_map:
                node.pairs = self.scalar_pairs(text[at + 1 : end], row, col + at + 1)
                node.size += 2 * len(node.pairs)
            else:
                node.items = self.scalar_items(text[at + 1 : end], row, col + at + 1)
                node.size += len(node.items)
        else:
            inside, end = self.entries(text, at, row, col, depth, close)
            for child in inside:
                node.size += child.size
            if is_map:
                node.pairs = list(zip(inside[0::2], inside[1::2], strict=True))
            else:
                node.items = inside
        node.closed = True
        return node, end + 1

    def scalar_pairs(self, inside: str, row: int, col: int) -> list[tuple[Node, Node]]:
        """The pairs of a flow mapping of plain scalars only (``inside`` its text between the
        braces, from column ``col``), as :meth:`scalar_cells` reads them."""
        return cell_pairs(self.scalar_cells(inside, row, col), self.file, row + 1)

    def scalar_cells(self, inside: str, row: int, col: int) -> list[Cell]:
        """The pairs of a flow mapping of plain scalars only (``inside`` its text between the
        braces, from column ``col``), one :data:`Cell` each: split, not scanned, typed inline
        (:meth:`plain` unrolled: most scalars of a large file are here)."""
        cells: list[Cell] = []
        if not inside.strip(" "):
            return cells
        typed, append, types = self.typed, cells.append, self.types
        at = col + 1
        for piece in inside.split(", "):  # written as most are, ``k: v, k: v``
            key, colon, text = piece.partition(": ")
            if (
                "," in piece
                or key[:1] == " "
                or key[-1:] == " "
                or text[-1:] == " "
                or (text[:1] == " ")
            ):
                return self._spaced_cells(inside, col)  # spaces to strip, or a comma
            if not colon or ":" in key or ":" in text or len(key) > MAX_KEY_LENGTH:
                raise GiveUp
            key_tag, key_value = (
                (STR, key) if key[:1] in TEXT_FIRST else types.get(key) or typed(key)
            )
            tag, value = (STR, text) if text[:1] in TEXT_FIRST else typed(text)
            append((key, at, key_tag, key_value, text, at + len(key) + 2, tag, value))
            at += len(piece) + 2
        return cells

    def _spaced_cells(self, inside: str, col: int) -> list[Cell]:
        """:meth:`scalar_cells` of a mapping written with other spaces around its signs."""
        cells: list[Cell] = []
        typed = self.typed
        for piece in inside.split(","):
            name = piece.lstrip(" ")
            at = col + len(piece) - len(name) + 1
            name, colon, rest = name.partition(": ")
            key = name.rstrip(" ")
            text = rest.strip(" ")
            if not colon or ":" in key or ":" in text or len(name) > MAX_KEY_LENGTH:
                raise GiveUp
            key_tag, key_value = (STR, key) if key[:1] in TEXT_FIRST else typed(key)
            where = at + len(name) + 2 + len(rest) - len(rest.lstrip(" "))
            tag, value = (STR, text) if text[:1] in TEXT_FIRST else typed(text)
            cells.append((key, at, key_tag, key_value, text, where, tag, value))
            col += len(piece) + 1
        return cells

    def scalar_items(self, inside: str, row: int, col: int) -> list[Node]:
        """The items of a flow list of plain scalars only, as :meth:`scalar_pairs` reads them."""
        nodes: list[Node] = []
        if not inside.strip(" "):
            return nodes
        for piece in inside.split(","):
            text = piece.lstrip(" ")
            nodes.append(self.plain(text.rstrip(" "), row + 1, col + len(piece) - len(text) + 1))
            col += len(piece) + 1
        return nodes

    def entries(
        self, text: str, at: int, row: int, col: int, depth: int, close: str
    ) -> tuple[list[Node], int]:
        """The nodes of the flow collection opening at ``text[at]``, scanned, and where it
        closes (keys and values in turn for a mapping)."""
        inside: list[Node] = []
        at = _SPACES.match(text, at + 1).end()  # type: ignore[union-attr]
        if text[at : at + 1] == close:
            return inside, at
        while True:
            if close == "}":
                found = _FLOW_PLAIN.match(text, at)
                if found is None:
                    raise GiveUp
                name = found[0].rstrip(" ")
                after = at + len(found[0])
                if text[after : after + 2] != ": " or len(found[0]) > MAX_KEY_LENGTH:
                    raise GiveUp
                inside.append(self.plain(name, row + 1, col + at + 1))
                at = _SPACES.match(text, after + 2).end()  # type: ignore[union-attr]
            value, at = self.flow_value(text, at, row, col, depth + 1)
            inside.append(value)
            at = _SPACES.match(text, at).end()  # type: ignore[union-attr]
            if text[at : at + 1] == close:
                return inside, at
            if text[at : at + 1] != ",":
                raise GiveUp
            at = _SPACES.match(text, at + 1).end()  # type: ignore[union-attr]
            if text[at : at + 1] in (close, ""):
                raise GiveUp  # a trailing comma: legal, but not followed here

    def flow_value(self, text: str, at: int, row: int, col: int, depth: int) -> tuple[Node, int]:
        """A value inside a flow collection, and where it ends."""
        first = text[at : at + 1]
        if first in ("{", "["):
            return self.flow(text, at, row, col, depth)
        if first in ("'", '"'):
            found = QUOTED.match(text, at)
            if found is None:
                raise GiveUp
            inside = found[0][1:-1]
            where = col + at + 1
            return Node(
                "scalar", self.file, row + 1, where, inside, first, STR, inside
            ), found.end()
        found = _FLOW_PLAIN.match(text, at)
        if found is None:
            raise GiveUp
        value = found[0].rstrip(" ")
        return self.plain(value, row + 1, col + at + 1), at + len(value)

    def plain(self, text: str, line: int, col: int) -> Node:
        """A plain scalar, typed as :class:`launchkit.safe_yaml._Composer` types it."""
        if text[:1] in TEXT_FIRST:
            return Node("scalar", self.file, line, col, text, _PLAIN_STYLE, STR, text)
        tag, value = self.typed(text)
        return Node("scalar", self.file, line, col, value, _PLAIN_STYLE, tag, text)

    def typed(self, text: str) -> tuple[str, Any]:
        """The tag and value of a plain scalar that may be something but text (giving up on
        one that may not begin so, and where the composer fails)."""
        known = self.types.get(text)
        if known is not None:
            return known
        if not _starts_plain(text):
            raise GiveUp
        if self.loader is None:
            self.loader = _LOADER("")
        tag = self.loader.resolve(yaml.ScalarNode, text, (True, False))
        if tag in (STR, _MERGE):
            known = tag, text
        elif len(text) > safe_yaml.MAX_NUMBER_LENGTH:
            raise GiveUp
        else:
            try:
                scalar = yaml.ScalarNode(tag, text, style=_PLAIN_STYLE)
                known = tag, self.loader.construct_object(scalar)
            except (yaml.constructor.ConstructorError, ValueError, OverflowError):
                raise GiveUp from None
        if len(text) < 100 and len(self.types) < 10_000:
            self.types[text] = known
        return known
