"""The block structure of :mod:`launchkit.safe_yaml_fast`'s subset of YAML, line by line."""

from __future__ import annotations

from collections.abc import Iterator

from launchkit.safe_yaml import Node
from launchkit.safe_yaml_fast.line_item import LineItem
from launchkit.safe_yaml_fast.scalars import (
    KEY,
    MAX_DEPTH,
    MAX_KEY_LENGTH,
    PLAIN,
    QUOTED,
    STR,
    TEXT_FIRST,
    FlowReader,
    GiveUp,
    first_bad,
    split_key,
)


class LineReader(FlowReader):
    """Block YAML's lines to nodes; ``self.indent``, ``self.body`` and ``self.row`` are the
    next line holding something (comments and trailing spaces removed), indent -1 at the end."""

    def __init__(self, text: str, file: str) -> None:
        super().__init__(file)
        self.given = 0  # items given by items()
        self.tags: set[str] = set()  # the names one_line has found to be plain keys
        self.lines = text.split("\n")
        bad = first_bad(text)
        self.stop = len(self.lines) if bad is None else text.count("\n", 0, bad)
        self.row = -1
        self.indent = -1
        self.body = ""

    def advance(self) -> None:
        """Move to the next line that holds something."""
        lines = self.lines
        row = self.row + 1
        while row < len(lines):
            if row >= self.stop:
                raise GiveUp
            line = lines[row]
            body = line.lstrip(" ")
            if body and body[0] != "#":
                indent = len(line) - len(body)
                if "#" in body:
                    cut = body.find("#")
                    if body[cut - 1] != " " or "'" in body or '"' in body:
                        raise GiveUp
                    body = body[:cut]
                self.row, self.indent, self.body = row, indent, body.rstrip(" ")
                if indent == 0 and body.startswith(("---", "...")):
                    raise GiveUp
                return
            row += 1
        self.row, self.indent, self.body = row, -1, ""

    def items(self, key: str) -> Iterator[Node | LineItem]:
        """The items of the list under ``key:``, the text's only key (an item written whole on
        one line as a :class:`LineItem`)."""
        self.advance()
        if (
            self.indent != 0
            or self.body != key + ":"
            or self.plain(key, self.row + 1, 1).tag != STR
        ):
            raise GiveUp
        self.advance()
        indent = self.indent
        if indent < 0 or not self.is_entry():
            raise GiveUp
        one_line, entry = self.one_line, self.entry
        while self.indent == indent and self.body.startswith("- "):
            item = one_line(indent) or entry(indent, 2)
            self.given += 1  # before the yield: a give-up comes after the consumer resumes
            yield item
        if self.indent >= 0:
            raise GiveUp  # a second key or document, or an error: the composer's to say

    def is_entry(self) -> bool:
        """Whether the line is a list item (``- ...``)."""
        return self.body.startswith("- ")

    def seq(self, depth: int) -> Node:
        """The block list whose first ``-`` is the current line's."""
        indent = self.indent
        node = Node("seq", self.file, self.row + 1, indent + 1)
        items = []
        while self.indent == indent and self.is_entry():
            on_one_line = self.one_line(indent)
            item = self.entry(indent, depth + 1) if on_one_line is None else on_one_line.node()
            node.size += item.size
            items.append(item)
        node.items = items
        node.closed = True
        return node

    def one_line(self, indent: int) -> LineItem | None:
        """The item on the current line if it is the usual ``- tag: {key: value, ...}`` of
        plain scalars, the whole item; then the line of the next. None for anything else: the
        general path reads it (this one is :meth:`entry`, :meth:`map` and :meth:`flow`
        unrolled, as most of a large file's lines are such items)."""
        body = self.body
        brace = body.find(": {")
        if brace < 0 or body[-1] != "}":
            return None
        name = body[2:brace]
        inner = body[brace + 3 : -1]
        if (
            "{" in inner
            or "}" in inner
            or "[" in inner
            or "]" in inner
            or "'" in inner
            or '"' in inner
            or (
                name not in self.tags
                and (name[-1:] == " " or len(name) > MAX_KEY_LENGTH or not KEY.fullmatch(name))
            )
        ):
            return None
        if len(self.tags) < 1000:  # a large file has a few tags: each checked once
            self.tags.add(name)
        row = self.row
        tag_col = indent + 3
        tag, value = (STR, name) if name[:1] in TEXT_FIRST else self.typed(name)
        cells = self.scalar_cells(inner, row, indent + brace + 3)
        self.advance()
        if self.indent > indent:  # more keys of the item below it: the general path reads it
            self.row, self.indent, self.body = row, indent, body
            return None
        return LineItem(self.file, row + 1, (name, tag_col, tag, value), tag_col + brace, cells)

    def entry(self, indent: int, depth: int) -> Node:
        """One ``- ...`` item of a list at ``indent``; after it, the line of the next."""
        if depth > MAX_DEPTH:
            raise GiveUp
        rest = self.body[2:]
        text = rest.lstrip(" ")
        col = indent + 2 + len(rest) - len(text)
        if split_key(text) is not None:
            node = self.map(col, text, depth)
        else:
            row = self.row
            self.advance()
            node = self.inline(text, row, col, depth)
        if self.indent > indent:
            raise GiveUp  # a scalar going on, or a line between two indents
        return node

    def map(self, indent: int, text: str, depth: int) -> Node:
        """The block mapping whose first key is at ``indent`` of the current line (``text``
        from there); after it, the first line not in it."""
        if depth > MAX_DEPTH:
            raise GiveUp
        node = Node("map", self.file, self.row + 1, indent + 1)
        pairs = []
        while True:
            found = split_key(text)
            if found is None:
                raise GiveUp
            row = self.row
            key = self.plain(found[0], row + 1, indent + 1)
            self.advance()
            if found[1] is None:
                value = self.block(indent, depth + 1)
            else:
                value = self.inline(found[1], row, indent + found[2], depth + 1)
                if self.indent > indent:
                    raise GiveUp  # a scalar going on, or a line between two indents
            pairs.append((key, value))
            node.size += key.size + value.size
            if self.indent != indent:
                break
            text = self.body
        if self.indent > indent:
            raise GiveUp
        node.pairs = pairs
        node.closed = True
        return node

    def block(self, indent: int, depth: int) -> Node:
        """A key's value written on the lines below the key (at ``indent``)."""
        if self.indent > indent:
            if self.is_entry():
                return self.seq(depth)
            if split_key(self.body) is not None:
                return self.map(self.indent, self.body, depth)
        elif self.indent == indent and self.is_entry():
            return self.seq(depth)  # the list's ``-`` under the key (an "indentless" list)
        raise GiveUp  # an empty value, a scalar on its own line, ...

    def inline(self, text: str, row: int, col: int, depth: int) -> Node:
        """A value written whole on one line: a flow collection, a quoted or plain scalar."""
        if text[:1] in ("{", "["):
            node, end = self.flow(text, 0, row, col, depth)
            if end != len(text):
                raise GiveUp
            return node
        if QUOTED.fullmatch(text):
            inside = text[1:-1]
            return Node("scalar", self.file, row + 1, col + 1, inside, text[0], STR, inside)
        if PLAIN.fullmatch(text):
            return self.plain(text, row + 1, col + 1)
        raise GiveUp
