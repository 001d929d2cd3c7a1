"""Large launch files are read as a stream (issue #17): each top-level XML element becomes its
action and is dropped before the rest of the file is parsed, and only a window of the text is
kept for columns; errors still name the file, line and column, and keep their precedence.

The speed and memory are measured by ``bench/big_file.py`` (docs/benchmarks.md); these tests
check the structure that bounds them, without timing.
"""

from __future__ import annotations

import gc
from pathlib import Path

import pytest

from launchkit.api import check_report
from launchkit.description.actions import SetConfiguration
from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Text
from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.base_entity import Entity
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.frontend.tags import standard_parser
from launchkit.frontend.xml.entity import SHARED_LENGTH, SHARED_VALUES, XmlEntity
from launchkit.frontend.xml.parser import XmlParser
from launchkit.frontend.xml.stream import CHUNK_SIZE
from launchkit.safe_yaml import list_items

ENTRIES = 20_000  # about 1.2 MB: several chunks


def _write(path: Path, body: list[str]) -> Path:
    path.write_text("<launch>\n" + "".join(f"  {line}\n" for line in body) + "</launch>\n")
    return path


class Probe(Action):
    """What the tree and the text window held when one element was parsed."""

    def __init__(self, siblings: int, window: int) -> None:
        super().__init__()
        self.siblings = siblings
        self.window = window


def _probe(entity: Entity, parser: ActionParser) -> Action:
    assert isinstance(entity, XmlEntity)
    entity.raw("n")
    root = entity.element.getparent()
    assert root is not None
    return Probe(len(root), len(entity.source.text))


def test_parsed_elements_are_released_and_the_text_is_a_window(tmp_path: Path) -> None:
    path = _write(tmp_path / "big.launch.xml", [f'<probe n="{"x" * 40}"/>'] * ENTRIES)
    size = path.stat().st_size
    assert size > 4 * CHUNK_SIZE
    actions = standard_parser()
    actions.register("probe", _probe)
    probes = LaunchLoader(actions).load(path).actions
    assert len(probes) == ENTRIES
    assert all(isinstance(p, Probe) for p in probes)
    # the whole tree would hold every element, the whole text every byte, for the last one
    assert max(p.siblings for p in probes if isinstance(p, Probe)) < ENTRIES / 2
    assert max(p.window for p in probes if isinstance(p, Probe)) < size / 2


def test_locations_deep_in_a_large_file_are_those_of_the_whole_tree(tmp_path: Path) -> None:
    lines = [f'<let name="v{i}" value="{"x" * 40}"/>' for i in range(ENTRIES)]
    lines[-3] = '<let name="late"\n     value="$(var missing"/>'  # a start tag on two lines
    path = _write(tmp_path / "big.launch.xml", lines).resolve()
    with pytest.raises(LaunchFileError) as streamed:
        LaunchLoader().load(path)
    with pytest.raises(LaunchFileError) as whole:
        XmlParser(standard_parser()).parse_whole(path.read_bytes(), path)
    assert streamed.value.location == whole.value.location
    assert str(streamed.value.location).startswith(f"{path}:{ENTRIES}:")  # value="$(var ...


def test_the_location_of_an_action_far_in_the_file(tmp_path: Path) -> None:
    lines = [f'<let name="v{i}" value="x"/>' for i in range(ENTRIES)]
    lines[-1] = '<let\n   name="last" value="y"/>'
    path = _write(tmp_path / "big.launch.xml", lines)
    last = LaunchLoader().load(path).actions[-1]
    assert isinstance(last, SetConfiguration)
    assert last.location is not None
    assert (last.location.line, last.location.col) == (ENTRIES + 1, 3)


def test_a_syntax_error_after_a_bad_element_is_the_one_reported(tmp_path: Path) -> None:
    lines = ["<nosuchtag/>"] + [f'<let name="v{i}" value="x"/>' for i in range(ENTRIES)]
    path = tmp_path / "broken.launch.xml"
    path.write_text("<launch>\n" + "".join(f"  {line}\n" for line in lines) + "  <let\n")
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert "malformed XML" in str(raised.value)


def test_the_first_bad_element_of_a_well_formed_file_is_reported(tmp_path: Path) -> None:
    lines = [f'<let name="v{i}" value="x"/>' for i in range(ENTRIES)]
    lines[5] = "<nosuchtag/>"
    lines[-5] = "<alsonot/>"
    path = _write(tmp_path / "bad.launch.xml", lines)
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert "unknown tag <nosuchtag>" in str(raised.value)
    assert str(raised.value.location) == f"{path.resolve()}:7:3"


def test_a_utf16_file_is_read_whole_with_the_same_locations(tmp_path: Path) -> None:
    path = tmp_path / "wide.launch.xml"
    text = '<?xml version="1.0" encoding="UTF-16"?>\n<launch>\n  <let name="a" value="$(x)"/>\n'
    path.write_bytes((text + "</launch>\n").encode("utf-16"))
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert str(raised.value.location).startswith(f"{path.resolve()}:3:")


def test_yaml_actions_are_composed_one_at_a_time(tmp_path: Path) -> None:
    # the file's end is malformed: composing it whole would fail before the first item
    text = "launch:\n- let: {name: a, value: b}\n- let: {name: c, value: d}\n- let: {name: [\n"
    items = list_items(text, tmp_path / "big.launch.yaml", "launch")
    first = next(items)
    assert first.kind == "map" and first.pairs[0][0].value == "let"
    with pytest.raises(LaunchFileError, match="malformed YAML"):
        list(items)


def test_yaml_errors_keep_their_precedence(tmp_path: Path) -> None:
    body = "".join(f"- let: {{name: v{i}, value: x}}\n" for i in range(ENTRIES))
    early_bad = "launch:\n- nosuchtag: {}\n" + body
    path = tmp_path / "bad.launch.yaml"
    path.write_text(early_bad + "- let: {name: [\n")  # and malformed at the end
    with pytest.raises(LaunchFileError, match="malformed YAML"):
        LaunchLoader().load(path)
    path.write_text(early_bad + "- let: {}\n  oops: {}\n")  # an item holding two tags
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert "holds several tags" in str(raised.value)  # as when the tree's entities came first
    path.write_text(early_bad + "other: 1\n")  # a second top-level key
    with pytest.raises(LaunchFileError, match="second top-level key"):
        LaunchLoader().load(path)
    path.write_text(early_bad)
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert str(raised.value.location) == f"{path.resolve()}:2:3"
    assert "nosuchtag" in str(raised.value)


def test_process_attributes_are_checked_in_one_order_whatever_the_order_written(
    tmp_path: Path,
) -> None:
    # <executable> reads only the attributes given, but in its table's order: the first bad one
    # in that order is reported (output before respawn), as when each was read in turn
    for written in ('respawn="maybe" output="loud"', 'output="loud" respawn="maybe"'):
        path = _write(tmp_path / "x.launch.xml", [f'<executable cmd="true" {written}/>'])
        with pytest.raises(LaunchFileError) as raised:
            LaunchLoader().load(path)
        assert "attribute 'output' of <executable> is 'loud'" in str(raised.value)
        column = 3 + len('<executable cmd="true" ') + written.index("output") + len('output="')
        assert str(raised.value.location) == f"{path.resolve()}:2:{column}"


def test_conditions_and_unknown_attributes_far_in_a_large_file(tmp_path: Path) -> None:
    lines = [f'<executable cmd="/bin/true" name="p{i}" if="$(var a)"/>' for i in range(ENTRIES)]
    lines[-2] = '<executable cmd="/bin/true"\n     unless="$(var a)"/>'
    lines[-3] = '<executable cmd="/bin/true" if="false"/>'
    path = _write(tmp_path / "big.launch.xml", lines).resolve()
    actions = LaunchLoader().load(path).actions
    first, last, literal = actions[0].condition, actions[-2].condition, actions[-3].condition
    assert first is not None and last is not None and last.negate
    assert str(first.location) == f"{path}:2:{3 + lines[0].index('if=') + len('if=') + 1}"
    assert str(last.location) == f"{path}:{ENTRIES + 1}:14"  # unless="... on its second line
    # a literal true/false/1/0 cannot fail: its place is not looked for
    assert literal is not None and literal.location is None
    lines[-5] = '<executable cmd="/bin/true" name="p" nmae="q"/>'
    _write(path, lines)
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    column = 3 + len('<executable cmd="/bin/true" name="p" nmae="')
    assert str(raised.value.location) == f"{path}:{ENTRIES - 3}:{column}"
    assert "unknown attribute 'nmae' on <executable>" in str(raised.value)
    assert "(expected one of: cmd, if, name, unless)" in str(raised.value)  # as before


@pytest.mark.parametrize("value", ["maybe", "$(var a)", "yes"])
def test_a_condition_that_fails_names_its_place(tmp_path: Path, value: str) -> None:
    # whether literal or not, a condition that is no true/false/1/0 fails at its attribute
    lines = ['<let name="a" value="maybe"/>', f'<executable cmd="/bin/true" if="{value}"/>']
    path = _write(tmp_path / "x.launch.xml", lines).resolve()
    with pytest.raises(LaunchkitError) as raised:
        check_report(path)
    assert str(raised.value.location) == f"{path}:3:{3 + lines[1].index('if=') + len('if=') + 1}"
    assert "invalid if condition" in str(raised.value)


def test_a_python_launch_files_code_runs_with_the_cycle_collector(tmp_path: Path) -> None:
    # a check pauses the collector while it reads and evaluates (large files), but not for a
    # Python launch file's own code, which may make garbage
    path = tmp_path / "probe.launch.py"
    path.write_text(
        "import gc\n"
        "from launch import LaunchDescription\n"
        "def generate_launch_description():\n"
        "    if not gc.isenabled():\n"
        "        raise RuntimeError('the collector is paused')\n"
        "    return LaunchDescription([])\n"
    )
    assert gc.isenabled()
    assert ": ok (1 file(s)" in check_report(path)
    assert gc.isenabled()


def _sources(entity: Entity, parser: ActionParser) -> Action:
    assert isinstance(entity, XmlEntity)
    probe = Probe(len(entity.source.plain_values), 0)
    probe.value = entity.value("v")  # type: ignore[attr-defined]
    return probe


def test_short_plain_values_are_one_object_per_file(tmp_path: Path) -> None:
    # a large file writes the same short values again and again (if="false"): one object
    # each, in a bounded table; longer values and substitutions get their own
    lines = [f'<let name="v{i}" value="false"/>' for i in range(3)]
    lines += [f'<let name="w" value="{"y" * (SHARED_LENGTH + 1)}"/>'] * 2
    lines += ['<let name="w" value="$(var v0)"/>'] * 2
    actions = LaunchLoader().load(_write(tmp_path / "a.launch.xml", lines)).actions
    values = [action.value for action in actions if isinstance(action, SetConfiguration)]
    assert values[0] is values[1] is values[2] and values[0] == (Text("false"),)
    assert values[3] is not values[4] and values[3] == values[4]
    assert values[5] is not values[6] and values[5] == values[6]
    again = LaunchLoader().load(_write(tmp_path / "b.launch.xml", lines[:1])).actions[0]
    assert isinstance(again, SetConfiguration) and again.value is not values[0]  # per file
    actions_parser = standard_parser()
    actions_parser.register("probe", _sources)
    path = _write(
        tmp_path / "c.launch.xml", [f'<probe v="n{i}"/>' for i in range(2 * SHARED_VALUES)]
    )
    probes = LaunchLoader(actions_parser).load(path).actions
    assert max(p.siblings for p in probes if isinstance(p, Probe)) == SHARED_VALUES
    assert [p.value for p in probes[-2:]] == [  # type: ignore[attr-defined]
        (Text(f"n{i}"),) for i in range(2 * SHARED_VALUES - 2, 2 * SHARED_VALUES)
    ]
