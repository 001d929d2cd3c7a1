"""What a new user reads first: the README's first screen and what it promises."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()
FIRST_SCREEN = README.split("\n## ", 1)[0]


def section(text: str, heading: str) -> str:
    """The text under ``## heading``, up to the next heading of that level."""
    return text.split(f"\n## {heading}\n", 1)[1].split("\n## ", 1)[0]


def test_the_first_screen_says_what_and_for_whom_then_gives_the_two_commands() -> None:
    intro, rest = FIRST_SCREEN.split("```sh\n", 1)
    sentences = re.findall(r"[^.]+\.(?:\s|$)", intro.split("\n", 2)[2].replace("\n", " "))
    assert len(sentences) == 2, sentences
    commands = rest.split("```", 1)[0].splitlines()
    assert len(commands) == 2
    assert commands[0].endswith("pip install . && launchkit run gazebo_and_rviz.launch.xml")
    # the suite as CI runs it
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert commands[1].endswith(" && python -m pytest -n 2")
    assert any(
        line.strip().endswith(" python -m pytest -n 2") or line == "python -m pytest -n 2"
        for line in ci
    )
    assert "(docs/seeds.md)" in FIRST_SCREEN and (ROOT / "docs" / "seeds.md").is_file()
    assert "chromium" in FIRST_SCREEN


def test_pkg_executables_is_shown_with_its_optional_package() -> None:
    # as ros2 pkg executables: without a package, every package's executables
    assert "executables [PKG]" in README
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "pkg", "executables"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    assert "robot_state_publisher robot_state_publisher" in result.stdout.splitlines()


def test_where_users_drive_the_robot_they_read_that_plus_x_backs_it_up() -> None:
    assert "+x" in section(README, "Driving the robot") and "backwards" in README
    viewer = (ROOT / "docs" / "viewer.md").read_text()
    assert "`i` (▲) sends `+x`, which drives the seed robot **backwards**" in viewer


def test_no_stray_output_files_at_the_root() -> None:
    tracked = subprocess.run(
        ["git", "ls-files", "--", "*.out"], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert tracked.stdout == ""
