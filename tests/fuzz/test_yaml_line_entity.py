"""The entity a large YAML launch file's one-line items get (``frontend/yaml/line_entity.py``,
issue 17) against the entity made from the composer's nodes: the same actions (with their
conditions, values and locations) or the same error (message, file, line, column), for
generated files of one-line items with the launch tags' own keys, of every value type, with
keys written twice, typed tags and keys, unknown keys and malformed substitutions."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from launchkit import safe_yaml_fast
from launchkit.description.launch_description import walk
from launchkit.errors import LaunchFileError
from launchkit.frontend.tags import standard_parser
from launchkit.frontend.yaml import parser as yaml_parser
from launchkit.frontend.yaml.line_entity import LineEntity
from launchkit.frontend.yaml.parser import YamlParser

PATH = Path("/tmp/lines.launch.yaml")

TAGS = ["let", "arg", "executable", "node", "log", "set_env", "unset_env", "include",
        "group", "timer", "push_ros_namespace", "set_parameter", "shutdown", "nope", "1",
        "true"]  # fmt: skip
KEYS = ["name", "value", "default", "description", "if", "unless", "cmd", "pkg", "exec",
        "message", "level", "children", "period", "respawn", "output", "namespace", "file",
        "cwd", "shell", "bogus", "1", "true", "null"]  # fmt: skip
VALUES = ["a", "v0", "talker", "/ns/topic", "x/y.z", "a b", "$(var a)", "$(env HOME)",
          "$(var", "$(nope x)", "a\\b", "true", "false", "yes", "1", "-1", "0x1F", "2.5",
          ".5", "-.inf", ".nan", "~", "null", "2001-12-14", "screen", "INFO", "(a)", "_x",
          "$(eval 1 + 2)", "aé"]  # fmt: skip
SPACES = ["", "", "", " "]


@st.composite
def one_line_item(draw: st.DrawFn) -> str:
    """``- tag: {key: value, ...}`` with the spacing varied around the signs."""
    pairs = draw(st.lists(st.tuples(st.sampled_from(KEYS), st.sampled_from(VALUES)), max_size=4))
    space = draw(st.sampled_from(SPACES))
    inner = f"{space},{draw(st.sampled_from([' ', ' ', '']))}".join(
        f"{key}: {draw(st.sampled_from(SPACES))}{value}" for key, value in pairs
    )
    return f"- {draw(st.sampled_from(TAGS))}: {{{space}{inner}{space}}}"


@pytest.fixture
def line_entities(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[object]]:
    """The entities the fast path made (to know the comparison is not between two composers)."""
    made: list[object] = []
    real = yaml_parser.line_entity

    def counted(parent: str, item: safe_yaml_fast.LineItem) -> object:
        entity = real(parent, item)
        made.append(entity)
        return entity

    monkeypatch.setattr(yaml_parser, "line_entity", counted)
    yield made


def outcome(text: str, threshold: int) -> list[str]:
    """Every action parsed (type, location and fields), or the error, with ``threshold``
    deciding whether the line reader reads the text."""
    saved = safe_yaml_fast.THRESHOLD
    safe_yaml_fast.THRESHOLD = threshold
    try:
        description = YamlParser(standard_parser()).parse_text(text, PATH)
    except LaunchFileError as error:
        return [f"{error.location}: {error} | {error.expected} | {error.hint}"]
    finally:
        safe_yaml_fast.THRESHOLD = saved
    return [f"{type(a).__name__} {a.location} {a!r}" for a in walk(description.actions)]


def assert_alike(text: str) -> None:
    assert outcome(text, 0) == outcome(text, 1 << 30), text


@given(st.lists(one_line_item(), min_size=1, max_size=12))
def test_generated_one_line_items_parse_alike(items: list[str]) -> None:
    assert_alike("launch:\n" + "\n".join(items) + "\n")


def test_the_usual_items_are_read_from_their_cells(line_entities: list[object]) -> None:
    text = "launch:\n" + "".join(
        f"- let: {{name: v{i}, value: $(var a)}}\n- arg: {{name: a{i}, default: 1}}\n"
        for i in range(50)
    )
    assert_alike(text)
    kinds = {type(entity).__name__ for entity in line_entities}
    assert kinds == {"LineEntity"} and len(line_entities) == 100


@pytest.mark.parametrize(
    "item",
    [
        "- let: {name: a, value: b, name: c}",  # a key twice
        "- let: {name: a, value: 1, value: 2}",  # a typed key twice
        "- 1: {name: a}",  # a typed tag
        "- let: {1: a, name: b, value: c}",  # a typed key
        "- group: {children: x}",  # children that are no list
        "- let: {name: a, value: $(var}",  # a malformed substitution, located in the line
        "- let: {name: a,  value: $(nope x)}",  # an unknown one, after two spaces
        "- let: {name: a, value: b, bogus: c}",  # an unknown key
        "- let: {name: a, value: b, bogus: 1}",  # an unknown key with a typed value
        "- arg: {name: a, default: .nan, description: ~}",
        "- executable: {cmd: x, respawn: true, if: yes}",
        "- log: {message: 2.5}",
        "- let: {}",
    ],
)
def test_explicit_items_parse_alike(item: str, line_entities: list[object]) -> None:
    assert_alike("launch:\n- let: {name: first, value: x}\n" + item + "\n")
    assert line_entities, "the line reader gave no line item"


def test_a_typed_value_is_read_through_the_nodes() -> None:
    text = "launch:\n- executable: {cmd: x, respawn: true, name: p}\n"
    safe_yaml_fast.THRESHOLD, saved = 0, safe_yaml_fast.THRESHOLD
    try:
        items = list(safe_yaml_fast.list_items(text, PATH, "launch"))
    finally:
        safe_yaml_fast.THRESHOLD = saved
    (item,) = items
    assert isinstance(item, safe_yaml_fast.LineItem)
    entity = yaml_parser.line_entity("launch", item)
    assert isinstance(entity, LineEntity)
    assert entity.typed_text("respawn", "bool") == "true"
    before = "- executable: {cmd: x, respawn: true, name: "
    assert entity.attribute_location("name").col == len(before) + 1
