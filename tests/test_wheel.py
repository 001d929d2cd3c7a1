"""The installed wheel carries the robot package's share files: ``$(find-pkg-share
robot_wheel)`` points inside site-packages and its launch files run from anywhere. It also
carries the browser viewer's page and its vendored libraries, every import resolving.

Offline and quick: the wheel is built without build isolation and installed into a fresh venv
without its dependencies; those (the closure of what the wheel declares, and nothing else) are
the test environment's installed copies, put on the venv's path with their commands in its
``bin``, where ``pip install`` would have put them.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import sysconfig
import venv
import zipfile
from email.parser import HeaderParser
from importlib.metadata import Distribution, distribution
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

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


def declared_requirements(wheel: Path) -> list[str]:
    """The wheel's ``Requires-Dist`` lines."""
    with zipfile.ZipFile(wheel) as archive:
        (name,) = [n for n in archive.namelist() if n.endswith(".dist-info/METADATA")]
        metadata = HeaderParser().parsestr(archive.read(name).decode())
    return metadata.get_all("Requires-Dist") or []


def dependency_closure(requirements: list[str]) -> list[Distribution]:
    """The installed distributions ``requirements`` need (without extras), and theirs."""
    found: dict[str, Distribution] = {}
    seen: set[tuple[str, frozenset[str]]] = set()
    pending = [(text, frozenset[str]()) for text in requirements]
    while pending:
        text, extras = pending.pop()
        requirement = Requirement(text)
        active = extras or frozenset({""})
        if requirement.marker and not any(
            requirement.marker.evaluate({"extra": e}) for e in active
        ):
            continue
        key = (canonicalize_name(requirement.name), frozenset(requirement.extras))
        if key in seen:
            continue
        seen.add(key)
        found[key[0]] = dist = distribution(requirement.name)
        pending += [(inner, key[1]) for inner in dist.requires or []]
    return list(found.values())


def link_dependencies(wheel: Path, env_dir: Path) -> None:
    """Give the venv the wheel's dependency closure from the test environment: each
    distribution's top-level files linked into a folder on the venv's path, and its console
    scripts written to the venv's ``bin``."""
    deps = env_dir / "deps"
    deps.mkdir()
    for dist in dependency_closure(declared_requirements(wheel)):
        assert dist.files is not None, f"{dist.metadata['Name']} lists no files"
        site = Path(str(dist.locate_file("")))
        for top in {file.parts[0] for file in dist.files} - {"..", "__pycache__"}:
            if not (deps / top).exists():
                (deps / top).symlink_to(site / top)
        for entry in dist.entry_points.select(group="console_scripts"):
            script = env_dir / "bin" / entry.name
            head = entry.attr.split(".")[0]
            script.write_text(
                f"#!{env_dir / 'bin' / 'python'}\nimport sys\nfrom {entry.module} import {head}\n"
                f"sys.exit({entry.attr}())\n"
            )
            script.chmod(0o755)
    purelib = sysconfig.get_path("purelib", vars={"base": str(env_dir)})
    (Path(purelib) / "test-dependencies.pth").write_text(f"{deps}\n")


def test_installed_wheel_has_the_robot_share_dir(tmp_path: Path) -> None:
    pip = [sys.executable, "-m", "pip"]
    # a home of its own: pip asks `rustc --version` for its user agent, and rustup's rustc
    # writes its settings into a home that has none
    pip_env = {**os.environ, "HOME": str(tmp_path / "home")}
    build = ["wheel", "-q", "--no-deps", "--no-build-isolation", "-w", tmp_path, REPO]
    run(*pip, *build, cwd=tmp_path, env=pip_env)
    (wheel,) = tmp_path.glob("launchkit-*.whl")
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=False)
    python = env_dir / "bin" / "python"
    install = ["--python", python, "install", "-q", "--no-deps", "--no-index", wheel]
    run(*pip, *install, cwd=tmp_path, env=pip_env)
    link_dependencies(wheel, env_dir)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    share = Path(
        run(
            env_dir / "bin" / "launchkit", "pkg", "share", "robot_wheel", cwd=elsewhere
        ).stdout.strip()
    )
    assert share.is_relative_to(env_dir), share
    assert (share / "launch_xml" / "hello.launch.xml").is_file()
    for name in ("display.launch.py", "gazebo.launch.py", "gazebo_and_rviz.launch.py"):
        assert (share / "launch" / name).is_file(), name
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
    # a stock package's interface files travel in the wheel too
    shown = run(
        env_dir / "bin" / "launchkit", "interface", "show", "turtlesim/msg/Pose", cwd=elsewhere
    )
    assert "float32 linear_velocity" in shown.stdout
    printed = run(
        env_dir / "bin" / "launchkit", "run", "gazebo_and_rviz.launch.xml", "--print", cwd=elsewhere
    )
    assert "spawn_entity" in printed.stdout and "robot_state_publisher" in printed.stdout
    assert str(share / "config" / "robot.rviz") in printed.stdout
    assert "launchkit.stock.gazebo_ros.gzserver" in printed.stdout
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
    # the tutorials' Python files, unchanged; xacro is found though the venv is not activated
    python_printed = run(
        launchkit, "run", "robot_wheel", "gazebo_and_rviz.launch.py", "--print",
        cwd=elsewhere, env={**os.environ, "PATH": "/usr/bin:/bin"},
    )  # fmt: skip
    assert "autogenerated by xacro" in python_printed.stdout
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
