"""Read a YAML file into located nodes, safely.

PyYAML's own composer recurses once per nesting level (libyaml's crashes the interpreter on a
few hundred thousand ``[``), and it hands back an alias as the very node it names, so walking a
"billion laughs" document visits 10^9 nodes. This module builds the node tree itself from the
parser's events (libyaml's when PyYAML has it: about 20x faster than the pure-Python parser),
in a loop, with three bounds: nesting depth, how many nodes aliases may add in total, and no
alias to a node that is still open (a recursive alias). Scalars are typed as ``yaml.safe_load``
types them. Every failure is a :class:`LaunchFileError` at the file, line and column it is
about; the text must be UTF-8.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import LaunchFileError, Location

#: The deepest nesting of mappings and lists accepted (launch files use about ten levels).
MAX_DEPTH = 100
#: How many nodes all aliases of a file may add together, once expanded.
MAX_ALIAS_NODES = 100_000

_Loader: type[yaml.SafeLoader] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_MERGE_TAG = "tag:yaml.org,2002:merge"
_DEFAULT_TAGS = {"tag:yaml.org,2002:map", "tag:yaml.org,2002:seq"}


@dataclass(eq=False)
class Node:
    """A YAML node: a mapping (``pairs``), a list (``items``) or a scalar (``value``)."""

    kind: str  # "map", "seq" or "scalar"
    location: Location
    value: Any = None
    style: str | None = None
    tag: str = ""
    pairs: list[tuple[Node, Node]] = field(default_factory=list)
    items: list[Node] = field(default_factory=list)
    size: int = 1
    closed: bool = False
    written: str = ""  # a scalar as written in the file

    @property
    def is_merge_key(self) -> bool:
        """Whether this is the ``<<`` of a merge."""
        return self.kind == "scalar" and self.tag == _MERGE_TAG

    @property
    def text_location(self) -> Location:
        """Where a scalar's text begins (after the opening quote of a quoted one)."""
        return self.location.shifted(1) if self.style in ("'", '"') else self.location


def read_text(path: Path, included_from: Location | None) -> str:
    """The file's text; bytes that are not UTF-8 are an error at their line and column."""
    try:
        data = path.read_bytes()
    except OSError as error:
        raise LaunchFileError(f"cannot read '{path}': {error.strerror}", included_from) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        col = error.start - (data.rfind(b"\n", 0, error.start) + 1) + 1
        raise LaunchFileError(
            f"the file is not UTF-8 text (byte 0x{data[error.start]:02x})",
            Location(str(path), line, col),
            expected="a UTF-8 encoded YAML file",
        ) from None


def compose(text: str, path: Path) -> Node | None:
    """The one document in ``text`` as a node tree (None for an empty file)."""
    return _Composer(text, path).run()


class _Composer:
    """Events to nodes, in a loop, with the bounds the module docstring lists."""

    def __init__(self, text: str, path: Path) -> None:
        self.path = path
        self.text = text
        self.loader: Any = _Loader(text)  # PyYAML's stubs leave the parser's methods untyped
        self.anchors: dict[str, Node] = {}
        self.alias_nodes = 0

    def where(self, mark: Any) -> Location:
        return Location(str(self.path), mark.line + 1, mark.column + 1)

    def run(self) -> Node | None:
        try:
            return self._document()
        except yaml.MarkedYAMLError as error:
            mark = error.problem_mark or error.context_mark
            problem = error.problem or error.context or "malformed YAML"
            raise LaunchFileError(
                f"malformed YAML: {problem}",
                self.where(mark) if mark is not None else Location(str(self.path)),
                expected="well-formed YAML",
            ) from None
        except yaml.YAMLError as error:  # a reader error: a character YAML does not allow
            raise LaunchFileError(
                f"malformed YAML: {getattr(error, 'reason', error)}",
                self._reader_location(error),
                expected="printable characters only",
            ) from None
        finally:
            self.loader.dispose()

    def _reader_location(self, error: yaml.YAMLError) -> Location:
        position = getattr(error, "position", None)
        if not isinstance(position, int):
            return Location(str(self.path))
        line = self.text.count("\n", 0, position) + 1
        return Location(
            str(self.path), line, position - (self.text.rfind("\n", 0, position) + 1) + 1
        )

    def _document(self) -> Node | None:
        loader = self.loader
        loader.get_event()  # stream start
        if loader.check_event(yaml.StreamEndEvent):
            return None
        loader.get_event()  # document start
        root = self._node()
        loader.get_event()  # document end
        if not loader.check_event(yaml.StreamEndEvent):
            raise LaunchFileError(
                "the file holds more than one YAML document",
                self.where(loader.peek_event().start_mark),
                expected="one document (no second '---')",
            )
        return root

    def _node(self) -> Node:
        """The next node, built without recursion: a stack of open collections."""
        stack: list[Node] = []
        while True:
            event = self.loader.get_event()
            node: Node | None = None
            if isinstance(event, yaml.AliasEvent):
                node = self._alias(event)
            elif isinstance(event, yaml.ScalarEvent):
                node = self._scalar(event)
                self._anchor(event, node)
            elif isinstance(event, yaml.SequenceStartEvent | yaml.MappingStartEvent):
                kind = "seq" if isinstance(event, yaml.SequenceStartEvent) else "map"
                self._check_tag(event, kind)
                opened = Node(kind, self.where(event.start_mark))
                self._anchor(event, opened)
                stack.append(opened)
                if len(stack) > MAX_DEPTH:
                    raise LaunchFileError(
                        f"the YAML nests more than {MAX_DEPTH} levels deep",
                        opened.location,
                        expected="a launch file of ordinary depth",
                    )
                continue
            else:  # the end of the innermost open collection
                node = stack.pop()
                node.closed = True
                if node.kind == "map":
                    flat = node.items
                    node.pairs = list(zip(flat[0::2], flat[1::2], strict=True))
                    node.items = []
                    node.size = 1 + sum(k.size + v.size for k, v in node.pairs)
                else:
                    node.size = 1 + sum(item.size for item in node.items)
            if not stack:
                return node
            stack[-1].items.append(node)

    def _scalar(self, event: yaml.ScalarEvent) -> Node:
        tag = event.tag
        if tag is None or tag == "!":
            tag = self.loader.resolve(yaml.ScalarNode, event.value, event.implicit)
        scalar = yaml.ScalarNode(tag, event.value, style=event.style)
        try:
            value = event.value if tag == _MERGE_TAG else self.loader.construct_object(scalar)
        except yaml.constructor.ConstructorError:
            raise LaunchFileError(
                f"YAML tag {tag!r} is not supported",
                self.where(event.start_mark),
                expected="a plain scalar (text, number, boolean)",
            ) from None
        return Node(
            "scalar",
            self.where(event.start_mark),
            value,
            event.style,
            tag,
            closed=True,
            written=event.value,
        )

    def _check_tag(self, event: yaml.CollectionStartEvent, kind: str) -> None:
        if event.tag is not None and event.tag != "!" and event.tag not in _DEFAULT_TAGS:
            raise LaunchFileError(
                f"YAML tag {event.tag!r} is not supported",
                self.where(event.start_mark),
                expected=f"a plain {'list' if kind == 'seq' else 'mapping'}",
            )

    def _anchor(self, event: yaml.NodeEvent, node: Node) -> None:
        if event.anchor is not None:
            self.anchors[event.anchor] = node

    def _alias(self, event: yaml.AliasEvent) -> Node:
        where = self.where(event.start_mark)
        target = self.anchors.get(event.anchor or "")
        if target is None:
            raise LaunchFileError(
                f"YAML alias *{event.anchor} names no anchor",
                where,
                expected=f"an anchor &{event.anchor} earlier in the file",
            )
        if not target.closed:
            raise LaunchFileError(
                f"YAML alias *{event.anchor} is inside the node it names",
                where,
                expected="an alias to a node that is complete where the alias is used",
            )
        self.alias_nodes += target.size
        if self.alias_nodes > MAX_ALIAS_NODES:
            raise LaunchFileError(
                f"YAML aliases expand to more than {MAX_ALIAS_NODES} nodes",
                where,
                expected="aliases that repeat a small part of the file",
                hint="aliases of aliases multiply (a 'billion laughs' document)",
            )
        return target
