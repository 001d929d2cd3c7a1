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

import stat
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import yaml

from launchkit.errors import LaunchFileError, Location

#: The deepest nesting of mappings and lists accepted (launch files use about ten levels).
MAX_DEPTH = 100
#: The largest YAML file read (launch files and params files are kilobytes).
MAX_FILE_SIZE = 256 * 1024 * 1024
#: How many nodes all aliases of a file may add together, once expanded.
MAX_ALIAS_NODES = 100_000
#: The longest scalar read as anything but text: a longer number costs quadratic time (YAML
#: 1.1's base-60 integers such as ``1:0:0:...``) or is refused by ``int()`` past 4300 digits.
MAX_NUMBER_LENGTH = 1000

_Loader: type[yaml.SafeLoader] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
MERGE_TAG = "tag:yaml.org,2002:merge"
_STR_TAG = "tag:yaml.org,2002:str"
_DEFAULT_TAGS = {"tag:yaml.org,2002:map", "tag:yaml.org,2002:seq"}


class Node:
    """A YAML node: a mapping (``pairs``), a list (``items``) or a scalar (``value``), with the
    line and column it begins at."""

    def __init__(
        self,
        kind: str,
        file: str,
        line: int,
        col: int,
        value: Any = None,
        style: str | None = None,
        tag: str = "",
        written: str = "",
    ) -> None:
        self.kind = kind  # "map", "seq" or "scalar"
        self.file = file
        self.line = line  # 1-based, as the file's text is counted
        self.col = col
        self.value = value
        self.style = style
        self.tag = tag
        self.written = written  # a scalar as written in the file
        self.pairs: Sequence[tuple[Node, Node]] = ()
        self.items: Sequence[Node] = ()
        self.size = 1  # nodes in it, itself included, aliases expanded
        self.closed = kind == "scalar"

    @property
    def location(self) -> Location:
        """Where the node begins."""
        return Location(self.file, self.line, self.col)

    @property
    def is_merge_key(self) -> bool:
        """Whether this is the ``<<`` of a merge."""
        return self.kind == "scalar" and self.tag == MERGE_TAG

    @property
    def text_location(self) -> Location:
        """Where a scalar's text begins (after the opening quote of a quoted one)."""
        return self.location.shifted(1) if self.style in ("'", '"') else self.location


def read_text(path: Path, included_from: Location | None) -> str:
    """The file's text; bytes that are not UTF-8 are an error at their line and column."""
    where = included_from or Location(str(path))
    try:
        status = path.stat()
        if not stat.S_ISREG(status.st_mode):  # /dev/zero or a FIFO would never end
            raise LaunchFileError("not a regular file", where, expected="a YAML file")
        if status.st_size > MAX_FILE_SIZE:
            raise LaunchFileError(
                f"the file is {status.st_size} bytes long",
                where,
                expected=f"a YAML file of at most {MAX_FILE_SIZE} bytes",
            )
        data = path.read_bytes()
    except OSError as error:
        raise LaunchFileError(f"cannot read '{path}': {error.strerror}", where) from None
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
        self.file = str(path)
        self.text = text
        self.loader: Any = _Loader(text)  # PyYAML's stubs leave the parser's methods untyped
        self.anchors: dict[str, Node] = {}
        self.alias_nodes = 0

    def where(self, mark: Any) -> Location:
        return Location(str(self.path), mark.line + 1, mark.column + 1)

    def run(self) -> Node | None:
        """The document's root node; PyYAML's errors as :class:`LaunchFileError`\\ s at their
        line and column."""
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
        stack: list[tuple[Node, list[Node]]] = []
        while True:
            event = self.loader.get_event()
            if isinstance(event, yaml.ScalarEvent):
                node = self._scalar(event)
                self._anchor(event, node)
            elif isinstance(event, yaml.AliasEvent):
                node = self._alias(event)
            elif isinstance(event, yaml.SequenceStartEvent | yaml.MappingStartEvent):
                kind = "seq" if isinstance(event, yaml.SequenceStartEvent) else "map"
                self._check_tag(event, kind)
                mark: Any = event.start_mark  # the parser's events always have one
                opened = Node(kind, self.file, mark.line + 1, mark.column + 1)
                self._anchor(event, opened)
                stack.append((opened, []))
                if len(stack) > MAX_DEPTH:
                    raise LaunchFileError(
                        f"the YAML nests more than {MAX_DEPTH} levels deep",
                        opened.location,
                        expected="a launch file of ordinary depth",
                    )
                continue
            else:  # the end of the innermost open collection
                node, inside = stack.pop()
                node.closed = True
                node.size = 1 + sum(child.size for child in inside)
                if node.kind == "map":
                    node.pairs = list(zip(inside[0::2], inside[1::2], strict=True))
                else:
                    node.items = inside
            if not stack:
                return node
            stack[-1][1].append(node)

    def _anchor(self, event: yaml.NodeEvent, node: Node) -> None:
        if event.anchor is not None:
            self.anchors[event.anchor] = node

    def _scalar(self, event: yaml.ScalarEvent) -> Node:
        tag = event.tag
        if tag is None or tag == "!":
            # only a plain scalar can be anything but text (quoted and block ones are text)
            plain = not event.style and event.tag is None
            tag = (
                self.loader.resolve(yaml.ScalarNode, event.value, event.implicit)
                if plain
                else _STR_TAG
            )
        if tag not in (_STR_TAG, MERGE_TAG) and len(event.value) > MAX_NUMBER_LENGTH:
            raise LaunchFileError(
                f"an unquoted {tag.rsplit(':', 1)[-1]} of {len(event.value)} characters",
                self.where(event.start_mark),
                expected=f"at most {MAX_NUMBER_LENGTH} characters, or quotes to make it text",
            )
        try:
            if tag in (_STR_TAG, MERGE_TAG):
                value = event.value
            else:
                scalar = yaml.ScalarNode(tag, event.value, style=event.style)
                value = self.loader.construct_object(scalar)
        except (yaml.constructor.ConstructorError, ValueError, OverflowError):
            raise LaunchFileError(
                f"YAML tag {tag!r} is not supported",
                self.where(event.start_mark),
                expected="a plain scalar (text, number, boolean)",
            ) from None
        mark: Any = event.start_mark  # the parser's events always have one
        line, col = mark.line + 1, mark.column + 1
        return Node("scalar", self.file, line, col, value, event.style, tag, event.value)

    def _check_tag(self, event: yaml.CollectionStartEvent, kind: str) -> None:
        if event.tag is not None and event.tag != "!" and event.tag not in _DEFAULT_TAGS:
            raise LaunchFileError(
                f"YAML tag {event.tag!r} is not supported",
                self.where(event.start_mark),
                expected=f"a plain {'list' if kind == 'seq' else 'mapping'}",
            )

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


def load_file(path: Path, included_from: Location | None = None) -> Any:
    """The plain Python value of the YAML file ``path``, as ``yaml.safe_load`` gives it, read
    within this module's bounds (None for an empty file); ``included_from`` locates an error in
    opening it. Every failure is a :class:`LaunchFileError` at its file and line."""
    root = compose(read_text(path, included_from), path)
    return None if root is None else plain(root)


def plain(node: Node) -> Any:
    """A node as plain Python values (dicts, lists, scalars); ``<<`` merges as PyYAML does.
    Recursion is bounded by :data:`MAX_DEPTH`, work by :data:`MAX_ALIAS_NODES`."""
    if node.kind == "scalar":
        return node.value
    if node.kind == "seq":
        return [plain(item) for item in node.items]
    explicit: dict[Any, Any] = {}
    merged: dict[Any, Any] = {}
    for key, value in node.pairs:
        if key.is_merge_key:
            for source in value.items if value.kind == "seq" else [value]:
                if source.kind != "map":
                    raise LaunchFileError(
                        "a '<<' merge of something that is not a mapping",
                        source.location,
                        expected="'<<: *anchor' naming a mapping, or a list of them",
                    )
                for name, item in plain(source).items():
                    merged.setdefault(name, item)
            continue
        if key.kind != "scalar":
            raise LaunchFileError(
                f"a {'list' if key.kind == 'seq' else 'mapping'} used as a mapping key",
                key.location,
                expected="a text or number key",
            )
        explicit[key.value] = plain(value)
    return {**merged, **explicit}
