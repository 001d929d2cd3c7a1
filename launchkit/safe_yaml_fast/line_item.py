"""An item of a large ``launch:`` list written whole on one line, kept as read until its nodes
are asked for."""

from __future__ import annotations

from typing import Any

from launchkit.safe_yaml import Node
from launchkit.safe_yaml_fast.scalars import STR, Cell, cell_pairs, plain_scalar


class LineItem:
    """``- tag: {key: value, ...}`` of plain scalars on one line: the tag and the pairs as
    :data:`~launchkit.safe_yaml_fast.scalars.Cell`\\ s, typed and located as the composer
    types and locates them. Most of a large file's items are such lines; a frontend reads the
    cells directly and asks for :meth:`node` (the very node the composer builds) only where it
    needs one, which makes reading such a file about a third cheaper than building every
    scalar's node."""

    __slots__ = ("cells", "file", "line", "map_col", "tag", "tag_col", "tag_tag", "tag_value")

    def __init__(
        self,
        file: str,
        line: int,
        tag: tuple[str, int, str, Any],
        map_col: int,
        cells: list[Cell],
    ) -> None:
        self.file = file
        self.line = line  # 1-based
        self.tag, self.tag_col, self.tag_tag, self.tag_value = tag
        self.map_col = map_col  # the 1-based column of the mapping's "{"
        self.cells = cells

    @property
    def tag_is_text(self) -> bool:
        """Whether the tag is read as text (not a number, a boolean, null, ...)."""
        return self.tag_tag == STR

    def node(self) -> Node:
        """The item's node: a mapping of the tag to the mapping of the cells."""
        file, line = self.file, self.line
        value = Node("map", file, line, self.map_col)
        value.pairs = cell_pairs(self.cells, file, line)
        value.size += 2 * len(value.pairs)
        value.closed = True
        item = Node("map", file, line, self.tag_col)
        item.size += 1 + value.size
        key = plain_scalar(file, line, self.tag_col, self.tag, self.tag_tag, self.tag_value)
        item.pairs = [(key, value)]
        item.closed = True
        return item
