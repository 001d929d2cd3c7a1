"""The command line: check, --print, --show-args, package commands and launch-file lookup."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.engine.launcher import run_launchkit as launchkit


def test_check_only_validates(tmp_path: Path) -> None:
    marker = tmp_path / "started"
    path = tmp_path / "a.launch.xml"
    path.write_text(f'<launch><executable cmd="touch {marker}"/></launch>')
    result = launchkit("check", str(path), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "ok" in result.stdout
    assert not marker.exists()


def test_print_shows_processes_and_runs_nothing(tmp_path: Path) -> None:
    marker = tmp_path / "started"
    path = tmp_path / "a.launch.xml"
    path.write_text(
        "<launch>\n"
        '  <arg name="who" default="me"/>\n'
        '  <set_env name="WHO" value="$(var who)"/>\n'
        f'  <executable name="toucher" cmd="touch {marker}" cwd="/tmp"/>\n'
        '  <timer period="2"><executable cmd="echo later"/></timer>\n'
        "</launch>"
    )
    result = launchkit("run", str(path), "who:=you", "--print", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert f"process toucher  ({path}:4:3)" in out
    assert f"cmd: touch {marker}" in out
    assert "cwd: /tmp" in out
    assert "env: WHO=you" in out
    assert "timer after 2 s:" in out and "cmd: echo later" in out
    assert not marker.exists()


def test_print_into_a_reader_that_stops_early_ends_quietly(tmp_path: Path) -> None:
    """``launchkit run FILE --print | head -1``: the status of a SIGPIPE, no traceback."""
    path = tmp_path / "big.launch.xml"
    body = "".join(f'  <executable name="p{n}" cmd="true"/>\n' for n in range(3000))
    path.write_text(f"<launch>\n{body}</launch>\n")
    read, write = os.pipe()
    proc = subprocess.Popen(
        [sys.executable, "-m", "launchkit", "run", str(path), "--print"],
        cwd=tmp_path,
        stdout=write,
        stderr=subprocess.PIPE,
        text=True,
    )
    os.close(write)
    with os.fdopen(read) as reader:
        assert reader.readline()  # the first line, then the reader goes away
    _, stderr = proc.communicate(timeout=60)
    assert "Traceback" not in stderr and "BrokenPipeError" not in stderr, stderr
    assert proc.returncode == 141


def test_show_args_lists_defaults_descriptions_and_choices(tmp_path: Path) -> None:
    path = tmp_path / "a.launch.xml"
    path.write_text(
        '<launch><arg name="mode" default="sim" description="where to run">'
        '<choice value="sim"/><choice value="real"/></arg><arg name="robot"/></launch>'
    )
    result = launchkit("run", str(path), "--show-args", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "'mode':" in result.stdout and "where to run" in result.stdout
    assert "Valid choices are: 'sim', 'real'" in result.stdout
    assert "(default: 'sim')" in result.stdout
    assert "'robot':" in result.stdout and "(required)" in result.stdout


def test_show_args_lists_the_arguments_of_included_files(tmp_path: Path) -> None:
    (tmp_path / "world.launch.xml").write_text(
        '<launch><arg name="world" default="empty" description="the world"/>'
        '<arg name="mode" default="other"/></launch>'
    )
    (tmp_path / "top.launch.xml").write_text(
        '<launch><arg name="mode" default="sim"/><arg name="sim" default="true"/>'
        '<group if="$(var sim)"><include file="$(dirname)/world.launch.xml"/></group></launch>'
    )
    result = launchkit("run", str(tmp_path / "top.launch.xml"), "--show-args", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    # as ros2 launch --show-args: the included file's too, the first declaration of a name wins
    assert out.index("'mode':") < out.index("'sim':") < out.index("'world':")
    assert out.count("'mode':") == 1 and "(default: 'sim')" in out
    world = ["'world':", "the world", "(default: 'empty')", "(declared conditionally)"]
    assert "\n        ".join(world) in out


# what `run` refuses before starting anything; `run --print` and `check` must refuse it too
REFUSED = {
    "undefined configuration": ('<executable cmd="echo $(var nope)"/>', "2:23", "'nope'"),
    "missing params file": (
        '<node pkg="robot_state_publisher" exec="robot_state_publisher">'
        '<param from="/no/such.yaml"/></node>',
        "2:64",
        "parameter file '/no/such.yaml' does not exist",
    ),
    "program not found": (
        '<let name="d" value="$(command \'xacro-not-installed x.xacro\')"/>',
        "2:22",
        "could not run",
    ),
    "bad if value": (
        '<arg name="x" default="maybe"/><group if="$(var x)"/>',
        "2:43",
        "invalid if condition 'maybe'",
    ),
    "unknown package": ('<node pkg="no_such_pkg" exec="x"/>', "2:1", "package 'no_such_pkg'"),
}


@pytest.mark.parametrize("case", sorted(REFUSED))
@pytest.mark.parametrize("command", [["run", "--print"], ["check"]])
def test_print_and_check_refuse_what_run_refuses(
    tmp_path: Path, case: str, command: list[str]
) -> None:
    body, where, what = REFUSED[case]
    path = tmp_path / "bad.launch.xml"
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    result = launchkit(command[0], str(path), *command[1:], cwd=tmp_path)
    assert result.returncode == 2, (result.stdout, result.stderr)
    assert result.stderr.startswith(f"{path}:{where}: error: "), result.stderr
    assert what in result.stderr
    assert "Traceback" not in result.stderr


def test_check_says_what_it_did_not_check(tmp_path: Path) -> None:
    path = tmp_path / "a.launch.xml"
    path.write_text(
        '<launch><arg name="sim" default="false"/><executable cmd="true"/>'
        '<group if="$(var sim)"><node pkg="no_such_pkg" exec="x"/></group></launch>'
    )
    result = launchkit("check", str(path), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        f"{path}: ok (1 file(s), 4 entities; with these arguments it starts 1 process(es))",
        "not checked: what an if/unless that is false with these arguments would include or "
        "start (pass other arguments to check it)",
    ]
    checked = launchkit("check", str(path), "sim:=true", cwd=tmp_path)
    assert checked.returncode == 2 and "package 'no_such_pkg' not found" in checked.stderr


def test_run_pkg_executable_runs_it_as_ros2_run_does(tmp_path: Path, ament_prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    ran = launchkit("run", "amentpkg", "tool", "--ros-args", "-p", "x:=1", cwd=tmp_path, env=env)
    assert ran.returncode == 0, ran.stderr
    assert ran.stdout == "tool ran with --ros-args -p x:=1\n"
    prefixed = launchkit("run", "--prefix", "echo via", "amentpkg", "tool", cwd=tmp_path, env=env)
    assert prefixed.stdout == f"via {ament_prefix}/lib/amentpkg/tool\n"
    # a package's launch file of that name comes first, as `launchkit run PKG FILE` always did
    twin = ament_prefix / "lib" / "amentpkg" / "hello.launch.xml"
    twin.write_text("#!/bin/sh\necho the executable\n")
    twin.chmod(0o755)
    launched = launchkit("run", "amentpkg", "hello.launch.xml", cwd=tmp_path, env=env)
    assert "from ament" in launched.stdout and "the executable" not in launched.stdout


def test_launch_is_run_under_ros2s_name(tmp_path: Path, ament_prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    result = launchkit("launch", "amentpkg", "hello.launch.xml", cwd=tmp_path, env=env)
    assert result.returncode == 0, result.stderr
    assert "from ament" in result.stdout


@pytest.mark.parametrize(
    "target", [["gazebo_and_rviz.launch.xml"], ["robot_wheel", "gazebo_and_rviz.launch.xml"]]
)
def test_an_argument_without_assignment_is_said_to_be_one(
    tmp_path: Path, target: list[str]
) -> None:
    # the file is found in the robot package's launch folders, not in the working folder
    result = launchkit("run", *target, "world", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr == (
        "error: 'world' is not a launch argument assignment (expected NAME:=VALUE)\n"
    )
    result = launchkit("run", *target, "world=obstacles", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.endswith("  hint: did you mean 'world:=obstacles'?\n")


@pytest.mark.parametrize(
    ("argv", "usage"),
    [
        (["run", "--bogus", "a.launch.xml"], "usage: launchkit run "),
        (["pkg", "list", "--bogus"], "usage: launchkit pkg list "),
        (["topic", "echo", "--bogus", "/x"], "usage: launchkit topic echo "),
    ],
)
def test_an_unknown_option_shows_the_subcommands_usage(
    tmp_path: Path, argv: list[str], usage: str
) -> None:
    result = launchkit(*argv, cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith(usage), result.stderr
    assert "error: unrecognized arguments: --bogus" in result.stderr


def test_pkg_commands_know_the_robot_package(tmp_path: Path) -> None:
    listed = launchkit("pkg", "list", cwd=tmp_path)
    assert "robot_wheel" in listed.stdout.split()
    share = launchkit("pkg", "share", "robot_wheel", cwd=tmp_path)
    assert (Path(share.stdout.strip()) / "launch_xml" / "hello.launch.xml").is_file()
    prefix = launchkit("pkg", "prefix", "robot_wheel", cwd=tmp_path)
    assert prefix.returncode == 0 and prefix.stdout.strip()
    missing = launchkit("pkg", "prefix", "no_such_pkg", cwd=tmp_path)
    assert missing.returncode == 2
    assert "package 'no_such_pkg' not found" in missing.stderr
    assert "AMENT_PREFIX_PATH" in missing.stderr


@pytest.fixture
def ament_prefix(tmp_path: Path) -> Path:
    """An AMENT_PREFIX_PATH prefix with package ``amentpkg``: a launch file and an executable."""
    prefix = tmp_path / "install"
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    (index / "amentpkg").touch()
    launch = prefix / "share" / "amentpkg" / "launch"
    launch.mkdir(parents=True)
    (launch / "hello.launch.xml").write_text('<launch><log message="from ament"/></launch>')
    (launch / "only_here.launch.xml").write_text('<launch><log message="only here"/></launch>')
    tool = prefix / "lib" / "amentpkg" / "tool"
    tool.parent.mkdir(parents=True)
    tool.write_text('#!/bin/sh\necho tool ran with "$@"\n')
    tool.chmod(0o755)
    return prefix


def test_run_pkg_file_from_ament_prefix(tmp_path: Path, ament_prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    result = launchkit("run", "amentpkg", "hello.launch.xml", cwd=tmp_path, env=env)
    assert result.returncode == 0, result.stderr
    assert "from ament" in result.stdout
    executed = launchkit("exec", "amentpkg", "tool", "x", cwd=tmp_path, env=env)
    assert executed.stdout.strip() == "tool ran with x"


def test_bare_file_name_is_found_in_package_launch_folders(
    tmp_path: Path, ament_prefix: Path
) -> None:
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    result = launchkit("run", "only_here.launch.xml", cwd=tmp_path, env=env)
    assert result.returncode == 0, result.stderr
    assert "only here" in result.stdout


def test_bare_file_name_in_several_packages_lists_them(tmp_path: Path, ament_prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    result = launchkit("run", "hello.launch.xml", cwd=tmp_path, env=env)
    assert result.returncode == 2
    assert "several packages" in result.stderr
    assert "amentpkg" in result.stderr and "launch_xml" in result.stderr


def test_file_in_current_directory_wins(tmp_path: Path, ament_prefix: Path) -> None:
    (tmp_path / "hello.launch.xml").write_text('<launch><log message="local"/></launch>')
    env = {"AMENT_PREFIX_PATH": str(ament_prefix)}
    result = launchkit("run", "hello.launch.xml", cwd=tmp_path, env=env)
    assert result.returncode == 0 and "local" in result.stdout


def test_example_launch_file_runs(tmp_path: Path) -> None:
    result = launchkit(
        "run",
        "robot_wheel",
        "hello.launch.xml",
        "greeting:=Salut",
        "count:=2",
        cwd=tmp_path,
        env={"ROS_LOG_DIR": str(tmp_path / "log")},
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "[talker-1] Salut number 2" in result.stdout
