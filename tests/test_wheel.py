"""The installed wheel carries the robot package's share files: ``$(find-pkg-share
robot_wheel)`` points inside site-packages and its launch files run from anywhere. It also
carries the browser viewer's page and its vendored libraries, every import resolving."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import venv
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def run(
    *argv: str | Path, cwd: Path, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """Run a command to completion, failing the test with its output if it fails."""
    result = subprocess.run(
        [str(a) for a in argv],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert result.returncode == 0, f"{argv} failed:\n{result.stdout}\n{result.stderr}"
    return result


def test_installed_wheel_has_the_robot_share_dir(tmp_path: Path) -> None:
    run(sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", tmp_path, REPO, cwd=tmp_path)
    (wheel,) = tmp_path.glob("launchkit-*.whl")
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    run(python, "-m", "pip", "install", "-q", wheel, cwd=tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    share = Path(
        run(
            env_dir / "bin" / "launchkit", "pkg", "share", "robot_wheel", cwd=elsewhere
        ).stdout.strip()
    )
    assert share.is_relative_to(env_dir), share
    assert (share / "launch_xml" / "hello.launch.xml").is_file()
    assert (share / "urdf" / "three_wheeled_robot.urdf").is_file()
    ran = run(
        env_dir / "bin" / "launchkit",
        "run",
        "robot_wheel",
        "hello.launch.xml",
        "count:=1",
        cwd=elsewhere,
    )
    assert "[talker-1] Hello number 1" in ran.stdout
    printed = run(
        env_dir / "bin" / "launchkit", "run", "gazebo_and_rviz.launch.xml", "--print", cwd=elsewhere
    )
    assert "spawn_entity" in printed.stdout and "robot_state_publisher" in printed.stdout
    assert str(share / "config" / "robot.rviz") in printed.stdout
    assert "launchkit.stock.gazebo_ros.server" in printed.stdout
    # xacro is a runtime dependency: tutorial launch files run $(command 'xacro ...')
    xacro = tmp_path / "xacro.launch.xml"
    xacro.write_text(
        "<launch><node pkg='robot_state_publisher' exec='robot_state_publisher'>"
        "<param name='robot_description' type='str' value=\"$(command 'xacro "
        f"{share / 'urdf' / 'three_wheeled_robot.urdf.xacro'}')\"/></node></launch>"
    )
    # as in the activated venv, and only it: the test's own environment has xacro too
    activated = {**os.environ, "PATH": f"{env_dir / 'bin'}{os.pathsep}/usr/bin{os.pathsep}/bin"}
    launchkit = env_dir / "bin" / "launchkit"
    printed = run(launchkit, "run", xacro, "--print", cwd=elsewhere, env=activated)
    assert "<robot" in printed.stdout
    check_viewer_files(python, elsewhere)


def check_viewer_files(python: Path, cwd: Path) -> None:
    """The installed viewer page: its files, and every module it imports, are in the wheel."""
    root = Path(
        run(
            python,
            "-c",
            "from launchkit.stock.rviz2.web_files import WEB_ROOT; print(WEB_ROOT)",
            cwd=cwd,
        ).stdout.strip()
    )
    assert "site-packages" in root.parts, root
    index = (root / "index.html").read_text()
    imports = json.loads(re.search(r'<script type="importmap">(.*?)</script>', index, re.S)[1])
    for target in imports["imports"].values():
        assert (root / target).exists(), target
    for linked in re.findall(r'(?:href|src)="([^":]+)"', index):  # stylesheet, preloads, main
        assert (root / linked).is_file(), linked
    for name in ("js/main.js", "style.css", "vendor/VENDORED.md", "vendor/three/LICENSE"):
        assert (root / name).is_file(), name
    modules = [*root.glob("js/*.js"), *root.glob("vendor/three/**/*.js")]
    assert len(modules) >= 10, modules
    for module in modules:
        for relative in re.findall(r"""from\s+['"](\.{1,2}/[^'"]+)['"]""", module.read_text()):
            assert (module.parent / relative).resolve().is_file(), f"{module}: {relative}"
