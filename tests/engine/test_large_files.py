"""Large launch files: errors and locations far into a file are those of a small one (the
file, line and column; the first error in document order, a syntax error before any), in XML
and YAML."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.api import check_report
from launchkit.description.actions import SetConfiguration
from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.frontend.launch_loader import LaunchLoader

ENTRIES = 5_000


def _write(path: Path, body: list[str]) -> Path:
    path.write_text("<launch>\n" + "".join(f"  {line}\n" for line in body) + "</launch>\n")
    return path


def test_a_location_deep_in_a_large_file(tmp_path: Path) -> None:
    lines = [f'<let name="v{i}" value="{"x" * 40}"/>' for i in range(ENTRIES)]
    lines[-3] = '<let name="late"\n     value="$(var missing"/>'  # a start tag on two lines
    path = _write(tmp_path / "big.launch.xml", lines).resolve()
    with pytest.raises(LaunchFileError) as raised:
        LaunchLoader().load(path)
    assert str(raised.value.location) == f"{path}:{ENTRIES}:26"  # the end of "$(var missing


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
    assert first is not None and last is not None and last.negate and literal is not None
    assert str(first.location) == f"{path}:2:{3 + lines[0].index('if=') + len('if=') + 1}"
    assert str(last.location) == f"{path}:{ENTRIES + 1}:14"  # unless="... on its second line
    assert str(literal.location) == f"{path}:{ENTRIES - 1}:{3 + lines[-3].index('if=') + 4}"
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
