"""One test per kind of bad input: the one-line message, its location, exit status 2, and
nothing started (each file begins with an executable that would leave a marker file)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.engine.launcher import run_launchkit as launchkit

PROLOGUE = '<launch>\n  <executable cmd="touch {marker}"/>\n'


CASES = {
    "xml syntax": ('  <log message="x">\n</launch>', 4, "malformed XML", "well-formed XML"),
    "unknown tag": ("  <nod pkg='a' exec='b'/>\n</launch>", 3, "unknown tag <nod>", "one of:"),
    "unknown attribute": (
        '  <log message="x" colour="red"/>\n</launch>',
        3,
        "unknown attribute 'colour' on <log>",
        "one of:",
    ),
    "unknown substitution": (
        '  <log message="$(find-pkg robot)"/>\n</launch>',
        3,
        "unknown substitution $(find-pkg)",
        "one of:",
    ),
    "malformed substitution": (
        '  <log message="$(var x"/>\n</launch>',
        3,
        "unterminated",
        "')'",
    ),
    "wrong argument count": (
        '  <log message="$(dirname x)"/>\n</launch>',
        3,
        "$(dirname)",
        "",
    ),
    "bad literal value": (
        '  <executable cmd="true" respawn="maybe"/>\n</launch>',
        3,
        "respawn",
        "a boolean",
    ),
    "bad output mode": (
        '  <executable cmd="true" output="loud"/>\n</launch>',
        3,
        "output",
        "screen",
    ),
    "missing required attribute": ("  <let name='x'/>\n</launch>", 3, "value", 'value="'),
    "if and unless together": (
        '  <log message="x" if="true" unless="true"/>\n</launch>',
        3,
        "if",
        "",
    ),
    "missing static include": (
        '  <include file="$(dirname)/missing.launch.xml"/>\n</launch>',
        3,
        "does not exist",
        "a path to a launch file",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_launch_file(tmp_path: Path, case: str) -> None:
    body, line, what, expected = CASES[case]
    marker = tmp_path / "started"
    launch_file = tmp_path / "bad.launch.xml"
    launch_file.write_text(PROLOGUE.format(marker=marker) + body)
    result = launchkit("run", str(launch_file), cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    first = result.stderr.splitlines()[0]
    assert first.startswith(f"{launch_file}:{line}:"), first
    assert ": error: " in first and what in first, first
    assert expected in result.stderr
    assert "Traceback" not in result.stderr + result.stdout
    assert not marker.exists(), "a process started although the file is bad"


def test_error_in_included_file_shows_the_include_chain(tmp_path: Path) -> None:
    child = tmp_path / "child.launch.xml"
    child.write_text("<launch>\n\n  <lg/>\n</launch>")
    parent = tmp_path / "parent.launch.xml"
    parent.write_text('<launch><include file="$(dirname)/child.launch.xml"/></launch>')
    result = launchkit("check", str(parent), cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith(f"{parent}:1:9 -> {child}:3:3: error: unknown tag <lg>")


def test_runtime_error_in_included_files_shows_the_include_chain(tmp_path: Path) -> None:
    (tmp_path / "c.launch.py").write_text(
        "from launch import LaunchDescription\n"
        "from launch.actions import ExecuteProcess\n"
        "from launch.substitutions import LaunchConfiguration\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        "        ExecuteProcess(cmd=['echo', LaunchConfiguration('nope')]),\n"
        "    ])\n"
    )
    (tmp_path / "b.launch.xml").write_text(
        '<launch>\n  <let name="f" value="$(dirname)/c.launch.py"/>\n'
        '  <include file="$(var f)"/>\n</launch>'  # known only when it runs
    )
    (tmp_path / "a.launch.xml").write_text(
        '<launch>\n  <include file="$(dirname)/b.launch.xml"/>\n</launch>'
    )
    for command in (["run"], ["run", "--print"], ["check"]):
        result = launchkit(command[0], str(tmp_path / "a.launch.xml"), *command[1:], cwd=tmp_path)
        assert result.returncode == 2, result.stderr
        chain = f"{tmp_path}/a.launch.xml:2:3 -> {tmp_path}/b.launch.xml:3:3 -> "
        assert f"{chain}{tmp_path}/c.launch.py:8: error: launch configuration 'nope'" in (
            result.stderr
        )


@pytest.fixture
def with_args(tmp_path: Path) -> Path:
    """A file with a required argument and a choice."""
    path = tmp_path / "args.launch.xml"
    marker = tmp_path / "started"
    path.write_text(
        PROLOGUE.format(marker=marker)
        + '  <arg name="robot"/>\n'
        + '  <arg name="mode" default="sim"><choice value="sim"/><choice value="real"/></arg>\n'
        + "</launch>"
    )
    return path


def test_missing_required_argument(with_args: Path) -> None:
    result = launchkit("run", str(with_args), cwd=with_args.parent)
    assert result.returncode == 2
    assert result.stderr.startswith(f"{with_args}:3:3: error:")
    assert "'robot'" in result.stderr and "robot:=" in result.stderr
    assert not (with_args.parent / "started").exists()


def test_choice_violation(with_args: Path) -> None:
    result = launchkit("run", str(with_args), "robot:=r", "mode:=fake", cwd=with_args.parent)
    assert result.returncode == 2
    assert result.stderr.startswith(f"{with_args}:4:3: error:")
    assert "'fake'" in result.stderr and "sim" in result.stderr and "real" in result.stderr
    assert not (with_args.parent / "started").exists()


def test_malformed_command_line_argument(with_args: Path) -> None:
    result = launchkit("run", str(with_args), "robot=r", cwd=with_args.parent)
    assert result.returncode == 2
    assert "'robot=r' is not a launch argument assignment (expected NAME:=VALUE)" in result.stderr
    assert "did you mean 'robot:=r'?" in result.stderr
    assert not (with_args.parent / "started").exists()


def test_missing_launch_file(tmp_path: Path) -> None:
    result = launchkit("run", "no_such.launch.xml", cwd=tmp_path)
    assert result.returncode == 2
    assert "no_such.launch.xml" in result.stderr
    assert "Traceback" not in result.stderr


def test_unknown_package(tmp_path: Path) -> None:
    result = launchkit("run", "no_such_pkg", "x.launch.xml", cwd=tmp_path)
    assert result.returncode == 2
    assert "package 'no_such_pkg' not found" in result.stderr


def test_debug_shows_the_traceback(tmp_path: Path) -> None:
    path = tmp_path / "bad.launch.xml"
    path.write_text("<launch><nope/></launch>")
    result = launchkit("run", "--debug", str(path), cwd=tmp_path)
    assert result.returncode == 2
    assert "Traceback" in result.stderr


def test_runtime_error_names_the_element_and_stops_everything(tmp_path: Path) -> None:
    path = tmp_path / "late.launch.xml"
    path.write_text(
        "<launch>\n"
        '  <executable name="sleeper" cmd="sleep 30" output="screen"/>\n'
        '  <timer period="0.2">\n'
        '    <log message="$(var never_defined)"/>\n'
        "  </timer>\n"
        "</launch>"
    )
    result = launchkit("run", str(path), cwd=tmp_path)
    assert result.returncode == 1
    combined = result.stdout + result.stderr
    assert f"{path}:4:" in combined and "never_defined" in combined
    assert "Traceback" not in combined
    assert "sleeper-1" in combined
