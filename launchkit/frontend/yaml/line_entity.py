"""The entity of a large YAML launch file's one-line item (``- let: {name: a, value: b}``),
read from the line reader's cells without a node per scalar.

A 50 MB file holds a million such scalars; building a located node for each, then the
entity's tables from them, was most of reading it (issue 17). This entity answers the tag
parsers from the cells directly while every key is text and every value it is asked for is
text, and makes the usual :class:`~launchkit.frontend.yaml.entity.YamlEntity` from the item's
node for anything else (a typed value, a ``param`` value, an error to place): what a parser
sees, errors and their locations included, is the same either way.
"""

from __future__ import annotations

from launchkit.description.substitutions.base import Text, Value
from launchkit.description.substitutions.grammar import parse_value
from launchkit.errors import Location
from launchkit.frontend.base_entity import Entity
from launchkit.frontend.yaml.entity import YamlEntity, action_entity
from launchkit.safe_yaml_fast import LineItem
from launchkit.safe_yaml_fast.scalars import STR

_NONE: frozenset[str] = frozenset()  # no key of another type


def line_entity(parent: str, item: LineItem) -> Entity:
    """The entity of ``item``, an entry of ``parent``'s list of actions: a
    :class:`LineEntity` when its tag and keys are text and written once (and none is
    ``children``), else what :func:`action_entity` makes of its node (or the error it raises)."""
    if not item.tag_is_text:
        return action_entity(parent, item.node())
    cells = item.cells
    texts = {key: text for key, _, key_tag, _, text, _, tag, _ in cells if tag == key_tag == STR}
    if len(texts) == len(cells) and "children" not in texts:  # the usual: all text, each once
        return LineEntity(item, texts, _NONE)
    texts = {}
    others: list[str] = []
    for key, _, key_tag, _, text, _, tag, _ in item.cells:
        if key_tag != STR or key in texts or key in others or key == "children":
            return action_entity(parent, item.node())
        if tag == STR:
            texts[key] = text
        else:
            others.append(key)
    return LineEntity(item, texts, frozenset(others))


class LineEntity(Entity):
    """A YAML entity whose keys and text values are read from a :class:`LineItem`'s cells
    (``texts``: the keys whose values are text, and those values; ``others``: the keys whose
    values have another type, read through the item's :class:`YamlEntity`)."""

    ATTRIBUTE = "key"
    SPLITS_LISTS = False

    def __init__(self, item: LineItem, texts: dict[str, str], others: frozenset[str]) -> None:
        self.tag = item.tag  # Entity.__init__'s fields, a call shorter (a hot path)
        self._read: set[str] = set()
        self._item = item
        self._texts = texts
        self._others = others
        self._full: YamlEntity | None = None

    def _entity(self) -> YamlEntity:
        """The usual entity of the item, sharing which keys were read."""
        if self._full is None:
            key, value = self._item.node().pairs[0]
            self._full = YamlEntity(self.tag, value, key.location)
            self._full._read = self._read  # one record of what the parsers read
        return self._full

    @property
    def location(self) -> Location:
        """Where the tag is written."""
        item = self._item
        return Location(item.file, item.line, item.tag_col)

    def attribute_location(self, name: str) -> Location:
        """Where the key's value begins."""
        if name not in self._texts:
            return self._entity().attribute_location(name)
        item = self._item
        col = next(cell[5] for cell in item.cells if cell[0] == name)
        return Location(item.file, item.line, col)

    def key_location(self, name: str) -> Location:
        """Where the key is written."""
        return self._entity().key_location(name)

    def attribute_names(self) -> list[str]:
        """The keys, in order."""
        return [cell[0] for cell in self._item.cells]

    def attribute_text(self, name: str) -> str | None:
        """A text key's string (None when absent or null); any other type is an error."""
        if name in self._others:
            return self._entity().attribute_text(name)
        return self._texts.get(name)

    def typed_text(self, name: str, native: str) -> str | None:
        """A key that may be a string or a ``native`` value (bool, float, int), as text."""
        if name in self._others:
            return self._entity().typed_text(name, native)
        return self._texts.get(name)

    def value(self, name: str, native: str | None = None) -> Value | None:
        """As :meth:`Entity.value`, read from the cells when the value is text."""
        text = self._texts.get(name)
        if text is None:
            if name in self._others:
                return self._entity().value(name, native)
            self._read.add(name)
            return None
        self._read.add(name)
        if "$" not in text and "\\" not in text:  # plain text: no location to find
            return (Text(text),) if text else ()
        return parse_value(text, self.attribute_location(name))

    def param_value(self, name: str, kind: str | None) -> tuple[Value, str | None] | None:
        """A parameter value with its YAML type kept, as :class:`YamlEntity` reads it."""
        return self._entity().param_value(name, kind)

    def assert_fully_read(self) -> None:
        """Reject unread keys, as :class:`YamlEntity` does."""
        read = self._read
        if not (read.issuperset(self._texts) and read.issuperset(self._others)):
            self._entity().assert_fully_read()

    def children(self) -> list[Entity]:
        """None: a line of plain scalars holds no list."""
        return []

    def label(self, tag: str | None = None) -> str:
        """``'tag'``."""
        return f"'{tag or self.tag}'"

    def example(self, name: str) -> str:
        """``name: ...``."""
        return f"{name}: ..."
