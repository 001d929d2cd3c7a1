"""One YAML launch entity as the tag parsers see it, in ROS's YAML spelling (``launch_yaml``).

An entity is a tag and its value: ``- log: {message: hi}``. The value is a mapping of keys
(``message``), or a list of child entities (``- group: [...]``). Inside a mapping:

* ``children`` is the list of child actions, each a one-key mapping (``- let: {...}``);
* a key whose value is a list of mappings is a list of sub-entities named after the key
  (``env: [{name: A, value: b}]``, ``param``, ``remap``, ``keep``, ``choice``, an include's
  ``arg``), which is how YAML writes XML's child elements;
* any other key is an attribute. Its YAML type is checked as ROS checks it: text attributes take
  strings, a few take a float, an integer or a boolean as well (the parsers say which), and
  ``null`` counts as absent.

A merge key (``<<: *common``) is honoured; a key written twice is an error.
"""

from __future__ import annotations

from collections.abc import Sequence

from launchkit.description.substitutions.base import Value
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.base_entity import Entity
from launchkit.frontend.yaml.param_value import param_value
from launchkit.frontend.yaml.scalars import describe, node_text
from launchkit.safe_yaml import Node

_NATIVE_TYPES: dict[str, tuple[type, ...]] = {"bool": (bool,), "float": (float,), "int": (int,)}
_EXPECTED = {
    "bool": "a boolean (true, false) or a string",
    "float": "a float such as 1.0 (ROS's YAML reader takes no integer here) or a string",
    "int": "an integer or a string",
}


class YamlEntity(Entity):
    """A tag of a YAML launch file and its value node."""

    ATTRIBUTE = "key"
    SPLITS_LISTS = False

    def __init__(self, tag: str, node: Node, where: Location) -> None:
        super().__init__(tag)
        self.node = node
        self._where = where
        self._attributes: dict[str, tuple[Node, Node]] = {}
        self._entries: list[tuple[str, Node]] = []  # (key, list) in order, "children" included
        if node.kind == "map":
            self._sort_keys(node)
        elif node.kind == "seq":
            self._entries.append(("children", node))
        else:
            raise LaunchFileError(
                f"'{tag}' is {describe(node)}",
                where,
                expected=f"a mapping of its keys ('{tag}: {{}}' for none) or a list of "
                "child entities",
            )

    def _sort_keys(self, node: Node) -> None:
        seen: dict[str, Node] = {}
        for key, value in _merged_pairs(node):
            if key.kind != "scalar" or not isinstance(key.value, str):
                raise LaunchFileError(
                    f"a key of '{self.tag}' is {describe(key)}",
                    key.location,
                    expected="key names (text)",
                )
            name = key.value
            if name in seen:
                raise LaunchFileError(
                    f"key '{name}' is written twice in '{self.tag}'",
                    key.location,
                    expected="each key once",
                )
            seen[name] = key
            # a list whose first item is a mapping holds sub-entities, as ROS's YAML reader decides
            if name == "children" or (
                value.kind == "seq" and value.items and value.items[0].kind == "map"
            ):
                self._entries.append((name, value))
            else:
                self._attributes[name] = (key, value)

    # -- Entity --------------------------------------------------------------------------------

    @property
    def location(self) -> Location:
        """Where the tag is written."""
        return self._where

    def attribute_location(self, name: str) -> Location:
        """Where the key's value begins."""
        found = self._attributes.get(name)
        return self._where if found is None else found[1].text_location

    def key_location(self, name: str) -> Location:
        """Where the key is written."""
        found = self._attributes.get(name)
        return self._where if found is None else found[0].location

    def attribute_names(self) -> list[str]:
        """The keys that are attributes, in order."""
        return list(self._attributes)

    def label(self, tag: str | None = None) -> str:
        """``'tag'``."""
        return f"'{tag or self.tag}'"

    def example(self, name: str) -> str:
        """``name: ...``."""
        return f"{name}: ..."

    def attribute_text(self, name: str) -> str | None:
        """A text key's string (None when absent or null); any other type is an error."""
        node = self._scalar(name)
        if node is None or isinstance(node.value, str):
            return None if node is None else node.value
        raise self._type_error(name, node, f"a string (quote it: '{node.written}')")

    def typed_text(self, name: str, native: str) -> str | None:
        """A key that may be a string or a ``native`` value (bool, float, int), as text."""
        node = self._scalar(name)
        if node is None or isinstance(node.value, str):
            return None if node is None else node.value
        value = node.value
        if isinstance(value, _NATIVE_TYPES[native]) and not (
            native == "int" and isinstance(value, bool)
        ):
            return node_text(node)
        raise self._type_error(name, node, _EXPECTED[native])

    def param_value(self, name: str, kind: str | None) -> tuple[Value, str | None] | None:
        """A parameter value with its YAML type kept (see ``param_value.py``)."""
        self._read.add(name)
        found = self._attributes.get(name)
        if found is None or (found[1].kind == "scalar" and found[1].value is None):
            return None
        return param_value(found[1], kind, f"key '{name}' of '{self.tag}'")

    def assert_fully_read(self) -> None:
        """Reject unread keys; an unread empty list is most likely an empty ``env: []``."""
        for name, (key, value) in self._attributes.items():
            if name not in self._read and value.kind == "seq" and not value.items:
                raise LaunchFileError(
                    f"key '{name}' of '{self.tag}' is an empty list",
                    key.location,
                    expected="a list of mappings, or no such key",
                )
        super().assert_fully_read()

    def children(self) -> list[Entity]:
        """Sub-entities of list keys and the ``children`` actions, in the order written."""
        out: list[Entity] = []
        for name, node in self._entries:
            if node.kind != "seq":
                raise LaunchFileError(
                    f"'children' of '{self.tag}' is {describe(node)}",
                    node.location,
                    expected="a list of child entities (- tag: {...})",
                )
            for item in node.items:
                out.append(self._action(item) if name == "children" else self._sub(name, item))
        return out

    # -- helpers -------------------------------------------------------------------------------

    def _scalar(self, name: str) -> Node | None:
        found = self._attributes.get(name)
        if found is None:
            return None
        node = found[1]
        if node.kind != "scalar":
            raise self._type_error(name, node, "a single value")
        return None if node.value is None else node

    def _type_error(self, name: str, node: Node, expected: str) -> LaunchFileError:
        return LaunchFileError(
            f"key '{name}' of '{self.tag}' is {describe(node)}",
            node.text_location,
            expected=expected,
        )

    def _action(self, item: Node) -> YamlEntity:
        return action_entity(self.tag, item)

    def _sub(self, name: str, item: Node) -> YamlEntity:
        if item.kind != "map":
            raise LaunchFileError(
                f"an item of '{name}' in '{self.tag}' is {describe(item)}",
                item.location,
                expected=f"a mapping such as {{name: ..., value: ...}} in every item of '{name}'",
            )
        return YamlEntity(name, item, item.location)


def action_entity(parent: str, item: Node) -> YamlEntity:
    """The entity of one item of ``parent``'s list of actions (``- tag: {...}``)."""
    if item.kind != "map" or not item.pairs:
        what = "an empty mapping" if item.kind == "map" else describe(item)
        raise LaunchFileError(
            f"an entry of '{parent}' is {what}",
            item.location,
            expected="one tag per list item (- tag: {...})",
        )
    if len(item.pairs) > 1:
        names = ", ".join(f"'{k.value}'" for k, _ in item.pairs)
        raise LaunchFileError(
            f"an entry of '{parent}' holds several tags ({names})",
            item.pairs[1][0].location,
            expected="one tag per list item: start each with '- '",
        )
    key, value = item.pairs[0]
    if key.kind != "scalar" or not isinstance(key.value, str):
        raise LaunchFileError(
            f"a tag in '{parent}' is {describe(key)}", key.location, expected="a tag name"
        )
    return YamlEntity(key.value, value, key.location)


def _merged_pairs(node: Node) -> Sequence[tuple[Node, Node]]:
    """The mapping's pairs with ``<<`` merges applied (its own keys win, as in YAML)."""
    if not any(key.is_merge_key for key, _ in node.pairs):
        return node.pairs
    own = [(k, v) for k, v in node.pairs if not k.is_merge_key]
    names = {k.value for k, _ in own}
    merged: list[tuple[Node, Node]] = []
    for key, value in node.pairs:
        if not key.is_merge_key:
            continue
        sources = value.items if value.kind == "seq" else [value]
        for source in sources:
            if source.kind != "map":
                raise LaunchFileError(
                    "a '<<' merge names something that is not a mapping",
                    source.location,
                    expected="<<: *anchor_of_a_mapping",
                )
            for k, v in _merged_pairs(source):
                if k.value not in names:
                    names.add(k.value)
                    merged.append((k, v))
    return own + merged
