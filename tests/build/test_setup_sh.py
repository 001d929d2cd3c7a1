"""`. install/setup.sh` (POSIX sh, from any folder, any number of times) and what launchkit
finds after it: the packages, their executables, their launch files through
`$(find-pkg-share)`."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import Built
from workspaces import environment, in_sourced_shell

from launchkit.testing import LaunchFactory


def test_after_sourcing_launchkit_lists_and_runs_the_built_executables(
    built: Built, tmp_path: Path
) -> None:
    env = environment(built.home)
    listed = in_sourced_shell(
        built.root,
        "launchkit pkg executables talker_py && launchkit pkg executables demo_user"
        " && launchkit exec talker_py talk one two && launchkit exec demo_user use"
        " && launchkit pkg list && launchkit pkg share demo_interfaces",
        env,
        cwd=tmp_path,  # not the workspace: the script names its folder itself
    )
    assert listed.returncode == 0, listed.stdout + listed.stderr
    lines = listed.stdout.splitlines()
    assert lines[:4] == ["talker_py talk", "demo_user use", "talk: one two", "demo_user runs"]
    # each line "NAME", or "NAME  (launchkit stand-in)"
    listed_names = {line.split()[0] for line in lines[4:-1]}
    assert {"talker_py", "demo_user", "demo_interfaces"} <= listed_names
    assert "talker_py" in lines  # a built package is the real one, not a stand-in
    assert lines[-1] == str(built.install / "demo_interfaces" / "share" / "demo_interfaces")


def test_sourcing_twice_changes_nothing_and_keeps_what_was_there(
    built: Built, tmp_path: Path
) -> None:
    underlay = "/opt/underlay"
    env = environment(built.home, AMENT_PREFIX_PATH=underlay, PYTHONPATH="/somewhere/site")
    once = in_sourced_shell(
        built.root, 'echo "$AMENT_PREFIX_PATH|$PYTHONPATH|$PATH"', env, tmp_path
    )
    twice = in_sourced_shell(
        built.root,
        f'. "{built.install}/setup.sh" && echo "$AMENT_PREFIX_PATH|$PYTHONPATH|$PATH"',
        env,
        tmp_path,
    )
    assert once.returncode == twice.returncode == 0, once.stderr + twice.stderr
    assert once.stdout == twice.stdout
    ament, python, path = once.stdout.strip().split("|")
    prefixes = ament.split(":")
    assert prefixes[-1] == underlay and len(prefixes) == len(set(prefixes)) == 4
    # a package comes before the ones it depends on, as colcon orders them
    assert prefixes.index(str(built.install / "demo_user")) < prefixes.index(
        str(built.install / "talker_py")
    )
    assert python.split(":")[-1] == "/somewhere/site"
    assert len(python.split(":")) == 3  # the two Python packages' site-packages, then it
    assert path == env["PATH"]  # the scripts are in lib/PKG: nothing for PATH


@pytest.mark.parametrize("file", ["talk.launch.xml", "talk.launch.py"])
def test_a_launch_file_of_a_built_package_finds_its_share_folder(
    built: Built, launch: LaunchFactory, tmp_path: Path, file: str
) -> None:
    # $(find-pkg-share talker_py) in XML, get_package_share_directory('talker_py') in Python
    sourced = in_sourced_shell(built.root, "env -0", environment(built.home), tmp_path)
    env = dict(item.split("=", 1) for item in sourced.stdout.split("\0") if "=" in item)
    handle = launch("talker_py", file, env=env, allow_exit={"talk": 0})
    talk = handle.process("talk")
    assert talk.wait_exit() == 0
    share = built.install / "talker_py" / "share" / "talker_py"
    talk.wait_output(f"talk: {share}/config/talk.yaml")
    talk.wait_output("    greeting: hi from the params file")
