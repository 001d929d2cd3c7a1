"""Issue #17, point 1: the launch files that used to end in a Python traceback (found by hand
and by the fuzzing harness, tests/fuzz) are each one located line and exit status 2, from both
``launchkit check`` and ``launchkit run``, and leave nothing running. The files are in
``corpus/``; a few too large to keep are written here."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.description.substitutions.grammar import MAX_DEPTH
from launchkit.frontend.action_parser import MAX_NESTING
from tests.hostile.helpers import CORPUS, assert_located_error, launchkit

#: file -> (where the error is, what it says), both regular expressions
CASES = {
    # non-UTF-8 bytes without a declaration: the byte's line and column
    "latin1_undeclared.launch.xml": (
        r"latin1_undeclared\.launch\.xml:2:30",
        "byte 0xe9 at offset 38 is not valid utf-8",
    ),
    # a file in UTF-16 is read as UTF-16: its errors have their lines too
    "utf16_bad_attribute.launch.xml": (
        r"utf16_bad_attribute\.launch\.xml:4:\d+",
        "unknown attribute 'colour'",
    ),
    # include cycles: the chain of includes, each at its file and line (RecursionError before)
    "self_include.launch.xml": (r"self_include\.launch\.xml:2:3", "include cycle.* itself"),
    "cycle_a.launch.xml": (
        r"cycle_a\.launch\.xml:2:3 -> \S*cycle_b\.launch\.xml:3:3",
        "include cycle: 'cycle_b.launch.xml' includes 'cycle_a.launch.xml' again",
    ),
    "self_include.launch.yaml": (r"self_include\.launch\.yaml:3:3", "include cycle"),
    "self_include.launch.py": (r"self_include\.launch\.py:13", "include cycle"),
    # names longer than the system allows (found by the fuzzer: an OSError before)
    "long_include_name.launch.yaml": (
        r"long_include_name\.launch\.yaml:4:3",
        "included launch file .* does not exist",
    ),
    "long_names.launch.xml": (r"long_names\.launch\.xml:3:\d+", "parameter file .* does not exist"),
    # Python launch files: the line in the user's file, no launchkit frames
    "syntax_error.launch.py": (r"syntax_error\.launch\.py:4:\d+", "invalid Python"),
    "raises_at_import.launch.py": (r"raises_at_import\.launch\.py:4", "KeyError: 'missing'"),
    "no_generate.launch.py": (r"no_generate\.launch\.py", "no generate_launch_description"),
    "calls_exit.launch.py": (r"calls_exit\.launch\.py:3", r"sys\.exit\(4\)"),
}


@pytest.mark.parametrize("command", ["check", "run"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_launch_file_is_one_located_line(name: str, command: str) -> None:
    where, message = CASES[name]
    assert_located_error(launchkit(command, CORPUS / name), where, message)


@pytest.mark.parametrize("command", ["check", "run"])
def test_substitutions_nested_too_deep_are_refused_with_the_limit(
    tmp_path: Path, command: str
) -> None:
    value = "x"
    for _ in range(400):  # a RecursionError before the limit
        value = f"$(var {value})"
    path = tmp_path / "deep.launch.xml"
    path.write_text(f'<launch>\n  <let name="y" value="{value}"/>\n</launch>\n')
    result = launchkit(command, path)
    assert_located_error(
        result, r"deep\.launch\.xml:2:\d+", f"substitutions nested deeper than {MAX_DEPTH}"
    )


def test_nesting_up_to_the_limit_still_works(tmp_path: Path) -> None:
    value = "v"
    for _ in range(MAX_DEPTH - 1):
        value = f"$(var {value})"
    path = tmp_path / "deep.launch.xml"
    path.write_text(
        '<launch>\n  <let name="v" value="v"/>\n'
        f'  <let name="y" value="{value}"/>\n  <log message="y=$(var y)"/>\n</launch>\n'
    )
    result = launchkit("run", path)
    assert result.returncode == 0, result.stderr
    assert "y=v" in result.stdout


@pytest.mark.parametrize("command", ["check", "run"])
def test_a_utf16_launch_file_is_read_in_its_declared_encoding(command: str) -> None:
    result = launchkit(command, CORPUS / "utf16.launch.xml")
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr


def test_a_non_ascii_value_of_a_utf16_file_reaches_the_process() -> None:
    result = launchkit("run", CORPUS / "utf16.launch.xml", "--print")
    assert result.returncode == 0, result.stderr
    assert "process utf16-café" in result.stdout


def test_a_file_included_twice_but_not_inside_itself_is_no_cycle(tmp_path: Path) -> None:
    (tmp_path / "leaf.launch.xml").write_text('<launch>\n  <log message="leaf"/>\n</launch>\n')
    top = tmp_path / "top.launch.xml"
    top.write_text(
        "<launch>\n"
        '  <include file="$(dirname)/leaf.launch.xml"/>\n'
        '  <include file="$(dirname)/leaf.launch.xml"/>\n'
        "</launch>\n"
    )
    result = launchkit("run", top)
    assert result.returncode == 0, result.stderr
    assert result.stdout.count("leaf") == 2


@pytest.mark.parametrize("command", ["check", "run"])
def test_actions_nested_too_deep_are_refused_with_the_limit(tmp_path: Path, command: str) -> None:
    depth = 250  # within lxml's 256 levels; a RecursionError before the limit
    path = tmp_path / "groups.launch.xml"
    path.write_text(
        "<launch>" + "<group>" * depth + '<log message="hi"/>' + "</group>" * depth + "</launch>"
    )
    assert_located_error(
        launchkit(command, path), r"groups\.launch\.xml:1:\d+", f"nested deeper than {MAX_NESTING}"
    )
    path.write_text(
        "<launch>" + "<group>" * (MAX_NESTING - 1) + '<log message="deep"/>'
        + "</group>" * (MAX_NESTING - 1) + "</launch>"
    )  # fmt: skip
    assert "deep" in launchkit("run", path).stdout


def test_a_launch_file_name_too_long_for_the_system_is_one_line() -> None:
    result = launchkit("check", "9" * 5000 + ".launch.xml")
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stderr.startswith("error: launch file '999")
