"""A launch that fails before it is ready fails the test at once with launchkit's message."""

from __future__ import annotations

import subprocess
import sys

import pytest

from launchkit.testing import LaunchFailed


def _launchkit_says(*argv: str) -> str:
    """What ``launchkit`` itself prints on stderr for ``argv``."""
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", *argv],
        capture_output=True,
        text=True,
        check=False,
        timeout=60,
    )
    assert done.returncode == 2, done
    return done.stderr.strip()


def test_a_malformed_file_fails_with_launchkits_message(launch, launch_dir):
    path = launch_dir / "bad.launch.xml"
    with pytest.raises(LaunchFailed) as caught:
        launch(path)
    expected = _launchkit_says("check", str(path))
    assert "bad.launch.xml:2:39: error: unknown substitution $(find-pkg)" in expected
    assert str(caught.value) == f"bad.launch.xml failed before it was ready:\n{expected}"


def test_a_missing_required_argument_fails_with_launchkits_message(launch, launch_dir):
    path = launch_dir / "required_arg.launch.xml"
    with pytest.raises(LaunchFailed, match=r"required argument 'speed' .* was not given"):
        launch(path)
    handle = launch(path, args={"speed": 3})  # given, it starts
    assert handle.process("echo").wait_exit(timeout=5) == 0
    assert handle.process("echo").output == ["3"]


def test_an_unknown_package_fails_with_launchkits_message(launch):
    with pytest.raises(LaunchFailed) as caught:
        launch("no_such_package", "x.launch.xml")
    assert _launchkit_says("run", "no_such_package", "x.launch.xml") in str(caught.value)


def test_a_process_that_cannot_be_spawned_fails_the_launch_at_once(launch):
    with pytest.raises(LaunchFailed) as caught:
        launch("launch/spawn_fails.launch.xml")
    message = str(caught.value)
    assert message.startswith("spawn_fails.launch.xml failed before it was ready:\n")
    # the folder is named, not the program (which exists); the launch itself would go on, as
    # in ROS, but a test sees the failure at once
    assert "lost-1: could not start process: its working folder " in message
    assert "'/nonexistent/launchkit-test-folder' does not exist" in message


def test_a_launcher_that_crashes_fails_the_launch_with_what_it_printed(launch):
    with pytest.raises(LaunchFailed) as caught:
        launch("launch/talker.launch.xml", env={"PYTHONHOME": "/nonexistent/python-home"})
    message = str(caught.value)
    assert message.startswith("talker.launch.xml ended before it was ready (launcher exit code")
    assert "Fatal Python error" in message  # what the launcher printed
