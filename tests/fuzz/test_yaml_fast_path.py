"""The line-by-line reader of large YAML launch files (``launchkit.safe_yaml_fast``, issue 17)
against PyYAML's composer (``launchkit.safe_yaml.list_items``), node for node and field for
field, errors (message, file, line, column) included. The size threshold is lowered so that
every text takes the fast path. Documents are generated inside the reader's subset of YAML
(where it must not give up) and just outside it, at the first item and after many (where it
must give up invisibly), and come from the fuzzing harness's YAML files and mutants."""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from launchkit import safe_yaml, safe_yaml_fast
from launchkit.errors import LaunchFileError
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.safe_yaml import Node, NotAList
from launchkit.safe_yaml_fast.line_item import LineItem
from launchkit.safe_yaml_fast.lines import LineReader
from launchkit.safe_yaml_fast.scalars import GiveUp
from tests.fuzz import strategies as S

ROOT = Path(__file__).resolve().parents[2]
PATH = Path("/tmp/fast.launch.yaml")


@pytest.fixture(autouse=True)
def _every_text_is_large(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(safe_yaml_fast, "THRESHOLD", 0)


def fields(node: Node) -> tuple[Any, ...]:
    """Every field of a node and of the nodes in it (a value by its type and repr: NaN)."""
    value = node.value
    shown = "nan" if isinstance(value, float) and math.isnan(value) else repr(value)
    return (
        node.kind, node.file, node.line, node.col, type(value), shown, node.style, node.tag,
        node.written, node.size, node.closed, type(node.pairs), type(node.items),
        tuple((fields(key), fields(item)) for key, item in node.pairs),
        tuple(fields(item) for item in node.items),
    )  # fmt: skip


def read(items: Iterator[Node | LineItem]) -> tuple[list[tuple[Any, ...]], str | None]:
    """The items given (a line item by its node), then the error that ended them (None:
    none)."""
    out = []
    try:
        for item in items:
            out.append(fields(item.node() if isinstance(item, LineItem) else item))
    except LaunchFileError as error:
        return out, f"{error.location}: {error}"
    except NotAList:
        return out, "not a list"
    return out, None


def assert_same(text: str) -> tuple[int, bool]:
    """The fast path gives what the composer gives; how many items, and whether the line reader
    read the whole text itself (no give-up)."""
    composed = read(safe_yaml.list_items(text, PATH, "launch"))
    fast = read(safe_yaml_fast.list_items(text, PATH, "launch"))
    assert fast[1] == composed[1]
    if composed[1] is None:
        assert fast[0] == composed[0]
    else:  # PyYAML reads ahead: its error may come an item sooner; the same error ends both
        shorter = min(len(fast[0]), len(composed[0]))
        assert fast[0][:shorter] == composed[0][:shorter]
    return len(composed[0]), read_whole(text)


def read_whole(text: str) -> bool:
    """Whether the line reader reads ``text`` without giving up."""
    try:
        for _ in LineReader(text, str(PATH)).items("launch"):
            pass
    except GiveUp:
        return False
    return True


# -- documents inside the subset -----------------------------------------------------------

BLOCK_PLAIN = [
    "a", "v0", "name", "value", "true", "no", "Yes", "off", "1", "-1", "0x1F", "1.5", ".5",
    "-.inf", ".nan", "~", "null", "Null", "2001-12-14", "$(var x)",
    "a b", "x/y.z", "aé", "+1", "0o17", "0b101", "1_000", "12e3", "x,y", "a=b", "_x", "(a)",
    "-0", "1e", "0.", "talker", "/ns/topic", "~/x", "190", "1.0e+3", "tRue", "y", "n",
    "$(eval '$(var a)' == 'b')", "robot's", 'a "b"',
]  # fmt: skip
FLOW_PLAIN = [s for s in BLOCK_PLAIN if not set(s) & set(",'\"")]
QUOTED = ["'a b'", '"x y"', "''", '""', "'$(var a)'", '"1"', "'true'", "'a: b'", '"é"']

key_text = st.sampled_from(["name", "value", "pkg", "exec", "let", "if", "1", "true", "a b"])


def spaces(draw: st.DrawFn) -> str:
    return draw(st.sampled_from(["", "", " ", "  "]))


@st.composite
def flow(draw: st.DrawFn, depth: int = 0) -> str:
    """A one-line flow mapping or list of plain (and a few quoted) scalars."""
    leaf = st.one_of(st.sampled_from(FLOW_PLAIN), st.sampled_from(QUOTED))
    value = leaf if depth > 1 else st.one_of(leaf, leaf, flow(depth + 1))
    if draw(st.booleans()):
        pairs = draw(st.lists(st.tuples(st.sampled_from(FLOW_PLAIN[:20]), value), max_size=4))
        inside = f"{spaces(draw)},{spaces(draw)}".join(
            f"{k}{draw(st.sampled_from(['', ' ']))}: {spaces(draw)}{v}" for k, v in pairs
        )
        return "{" + spaces(draw) + inside + spaces(draw) + "}"
    items = draw(st.lists(value, max_size=4))
    return "[" + spaces(draw) + f"{spaces(draw)},{spaces(draw)}".join(items) + spaces(draw) + "]"


def inline(draw: st.DrawFn) -> str:
    """A value on the key's or dash's line."""
    return draw(st.one_of(st.sampled_from(BLOCK_PLAIN), st.sampled_from(QUOTED), flow()))


def comment(draw: st.DrawFn, line: str) -> str:
    """A line, maybe with trailing spaces or a comment (never after quotes: given up on)."""
    if "'" in line or '"' in line:
        return line
    return line + draw(st.sampled_from(["", "", "  ", " # note", "   #: x"]))


@st.composite
def block_map(draw: st.DrawFn, indent: int, depth: int, first: str = "") -> list[str]:
    """A block mapping's lines at ``indent`` (its first key after ``first`` if given)."""
    lines: list[str] = []
    for number in range(draw(st.integers(1, 3))):
        head = first if number == 0 and first else " " * indent
        key = draw(key_text) + draw(st.sampled_from(["", "", " "]))
        nested = depth < 3 and draw(st.integers(0, 3)) == 0
        if not nested:
            lines.append(comment(draw, f"{head}{key}: {inline(draw)}"))
            continue
        lines.append(comment(draw, f"{head}{key}:"))
        kind = draw(st.sampled_from(["map", "seq", "indentless"]))
        deeper = indent + draw(st.sampled_from([2, 4]))
        if kind == "map":
            lines += draw(block_map(deeper, depth + 1))
        else:
            lines += draw(block_seq(indent if kind == "indentless" else deeper, depth + 1))
        if draw(st.integers(0, 4)) == 0:
            lines.append(draw(st.sampled_from(["", "# between", "      # deep", "  "])))
    return lines


@st.composite
def block_seq(draw: st.DrawFn, indent: int, depth: int) -> list[str]:
    """A block list's lines, its dashes at ``indent``."""
    lines: list[str] = []
    for _ in range(draw(st.integers(1, 3))):
        lines += draw(item(indent, depth))
    return lines


@st.composite
def item(draw: st.DrawFn, indent: int, depth: int) -> list[str]:
    """One ``- ...`` item: a compact mapping, or a value on the dash's line."""
    dash = " " * indent + "-" + draw(st.sampled_from([" ", " ", "  "]))
    if depth < 3 and draw(st.integers(0, 2)) > 0:
        return draw(block_map(len(dash), depth + 1, first=dash))
    return [comment(draw, dash + inline(draw))]


@st.composite
def launch_lines(draw: st.DrawFn) -> tuple[str, list[list[str]]]:
    """``launch:`` and its items' lines, each item a list of lines."""
    indent = draw(st.sampled_from([0, 2]))
    items = draw(st.lists(item(indent, 1), min_size=1, max_size=6))
    return "launch:", items


def join(head: str, items: list[list[str]]) -> str:
    return "\n".join([head, *(line for lines in items for line in lines)]) + "\n"


@given(launch_lines())
def test_documents_inside_the_subset_are_read_whole_and_alike(doc: Any) -> None:
    count, whole = assert_same(join(*doc))
    assert whole, join(*doc)
    assert count == len(doc[1])


# -- just outside the subset: each give-up trigger, first or after many items ---------------

OUTSIDE = [
    "\t- let: {name: a}", "- let: {name: a}\r", "- let: {name: \x85a}", "- a: b\u2028c",
    "\ufeff- a: b", "---", "...", "--- ", "%YAML 1.1", "- &a x: y", "- *a", "- !t x",
    "- a: !!str 1", "- a: |\n    text", "- a: >\n    text", "- ? a\n  : b", "- a: b\n  c",
    "- {a: b,\n  c: d}", "- [a,\n  b]", "- a:\n- b", "- a: b: c", "- a: b #c d", "- a: x#y",
    "- a: " + "1" * 1001, "- a: \x00", "- a: \x7f", "- a:\tb", "- [a, b]: c", "- a: -",
    "- a: @x", "- a: `x", "- a: 'it''s'", '- a: "x\\ty"', "- a: {b: c,}", "- a: [b, c,]",
    "  - a: b", "- - a", "-", "- ", "x: y", "- <<: {a: b}", "- a: =", "- a: 1:20",
    "- a: {b: c}}", "- a: [b]]", "- a: {b}", "- a: {b: }", "- a: {b:c}", "- a: {? b: c}",
    "- a: %x", "- a: ", "- a:", "- a: b\n   c: d", "- a: b\n c: d", "- a: 'x' y",
    "- a: 0x" + "f" * 1000, "- a: 1e999", "- a: 2001-02-30", "- a: &b [1]", "- é: 1",
    "- a: {é: 1}", "- a: [é]", "#" * 3, "- " + "k" * 1030 + ": v", "- {" + "k" * 1030 + ": v}",
    "- a: [" + "[" * 40 + "]" * 40 + "]", "- a: " + "b" * 70_000, "- a: 12:30:00",
    "- a:\n" + "".join("  " * i + f"  k{i}:\n" for i in range(40)) + "  " * 41 + "v: 1",
    "- " + "9" * 1030 + "let: {a: b}", "- a" + " " * 1030 + ": b", "- {a" + " " * 1030 + ": b}",
    "- a: {b" + " " * 1030 + ": c}", "- a:\n    b" + " " * 1030 + ": c",
    "- a: {b: c} d", "- a: [b] # x", "- a: b  ", "- 'a': b", "- a: '#'", "- a: \"'\"",
]  # fmt: skip


@given(
    launch_lines(),
    st.sampled_from(OUTSIDE),
    st.sampled_from(["first", "last", "middle"]),
    st.integers(0, 200),
)
def test_documents_just_outside_the_subset_give_up_invisibly(
    doc: Any, trigger: str, where: str, padding: int
) -> None:
    head, items = doc
    items = items + [["- let: {name: v, value: x}"]] * padding
    at = {"first": 0, "last": len(items), "middle": len(items) // 2}[where]
    items = [*items[:at], trigger.split("\n"), *items[at:]]
    assert_same(join(head, items))


@given(
    launch_lines(),
    st.integers(0, 10_000),
    st.sampled_from(["\t", "\r", "#", ":", " ", "'", '"', "{", "}", "[", "]", ",", "-", "&",
                     "*", "!", "|", ">", "?", "%", "@", "\n", "\n- ", ": ", " #", "\x85", "é"]),
)  # fmt: skip
def test_one_character_more_anywhere(doc: Any, at: int, extra: str) -> None:
    text = join(*doc)
    at %= len(text)
    assert_same(text[:at] + extra + text[at:])


@given(st.one_of(S.yaml_launch_file(), S.mutant_of(S.seeds("tests/corpus/yaml/*.yaml"))))
def test_the_fuzzing_harness_yaml_files(data: bytes) -> None:
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        assume(False)
        return
    assert_same(text)


# -- explicit cases ----------------------------------------------------------------------------


def test_the_benchmark_file_is_read_whole_and_alike(tmp_path: Path) -> None:
    sys.path.insert(0, str(ROOT / "bench"))
    try:
        import big_file
    finally:
        sys.path.remove(str(ROOT / "bench"))
    text = big_file.write_files(tmp_path, 3000)["yaml lets"].read_text()
    assert assert_same(text) == (3000, True)


@pytest.mark.parametrize(
    "name", sorted(p.name for p in (ROOT / "tests/corpus/yaml").glob("*.yaml"))
)
def test_the_corpus_launch_files(name: str) -> None:
    text = (ROOT / "tests/corpus/yaml" / name).read_text()
    count, whole = assert_same(text)
    # the corpus's nested node/param blocks, indentless lists and flow lists are in the subset
    assert whole and count > 0


NESTED = """\
launch:
- arg: {name: robot, default: r1}
- group:
    - push_ros_namespace:
        namespace: $(var robot)
    - node:
        pkg: demo_nodes_cpp
        exec: talker
        name: talker  # the talker
        output: screen
        param:
        - name: rate
          value: 2.5
        - {name: enabled, value: true}
        - name: list
          value: [1, 2, 3]
        remap:
        -   from: chatter
            to: /chat
        env: [{name: A, value: b}]
- let:
    name: v
    value: '0x1F'
"""


def test_nested_node_and_param_blocks() -> None:
    text = NESTED + "".join(f"- let: {{name: v{i}, value: {i}}}\n" for i in range(2000))
    assert assert_same(text) == (2003, True)


def test_an_error_late_in_a_large_file_is_the_composers(tmp_path: Path) -> None:
    text = "launch:\n" + "".join(f"- let: {{name: v{i}, value: x}}\n" for i in range(5000))
    text += "- let: {name: [\n"
    count, whole = assert_same(text)
    assert not whole and count >= 4999
    path = tmp_path / "late.launch.yaml"
    path.write_text(text)
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert str(raised.value.location) == f"{path.resolve()}:5003:1"


def test_a_give_up_late_in_a_large_file_is_invisible() -> None:
    lets = [f"- let: {{name: v{i}, value: x}}\n" for i in range(6000)]
    text = "launch:\n" + "".join(lets[:5000]) + "- let: &a {name: a, value: b}\n"
    text += "- let: *a\n" + "".join(lets[5000:])
    reader = LineReader(text, str(PATH)).items("launch")
    given = 0
    with pytest.raises(GiveUp):
        for _ in reader:
            given += 1
    assert given == 5000
    assert assert_same(text) == (6002, False)


def test_an_unquoted_number_too_long_late_in_a_large_file() -> None:
    text = "launch:\n" + "".join(f"- let: {{name: v{i}, value: x}}\n" for i in range(3000))
    text += "- let: {name: n, value: " + "1" * 1001 + "}\n"
    count, whole = assert_same(text)
    assert (count, whole) == (3000, False)


def test_small_texts_keep_the_composer(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(safe_yaml_fast, "THRESHOLD", 1 << 30)
    made: list[LineReader] = []
    monkeypatch.setattr(LineReader, "advance", made.append)
    items, error = read(safe_yaml_fast.list_items("launch:\n- a: b\n", PATH, "launch"))
    assert (len(items), error, made) == (1, None, [])
