"""Fixtures for the engine tests: ``launchkit run`` driven directly (see launcher.py), and a
package index with one Python package for the parse-level tests of ``<node>``."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from launchkit.packages import PackageIndex, PythonPackage
from tests.engine.launcher import Launcher, wait_gone


def write(tmp_path: Path, body: str, name: str = "t.launch.xml") -> Path:
    """A launch file with ``body`` inside ``<launch>``."""
    path = tmp_path / name
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


@pytest.fixture
def launchers(tmp_path: Path) -> Iterator[Callable[..., Launcher]]:
    """Start ``launchkit run FILE ARGS`` in the test's folder, logging there (``env`` adds to
    the test's environment); every launcher, and what it said it started, is killed at the end."""
    started: list[Launcher] = []

    def start(path: Path, *args: str, env: dict[str, str] | None = None) -> Launcher:
        environment = {"ROS_LOG_DIR": str(tmp_path), **(env or {})}
        launcher = Launcher(str(path), *args, cwd=tmp_path, env=environment)
        started.append(launcher)
        return launcher

    yield start
    for launcher in started:
        if launcher.proc.poll() is None:
            launcher.kill()
        launcher.close()
        wait_gone(list(launcher.pids.values()))


@pytest.fixture
def run(tmp_path: Path, launchers: Callable[..., Launcher]) -> Callable[..., Launcher]:
    """Start ``launchkit run`` on a launch file body (see ``launchers``)."""

    def start(body: str, *args: str) -> Launcher:
        return launchers(write(tmp_path, body), *args)

    return start


@pytest.fixture
def packages(tmp_path: Path) -> PackageIndex:
    """One Python package ``demo`` with a ``talker`` executable."""
    share = tmp_path / "demo_share"
    share.mkdir()
    return PackageIndex(
        ament_prefix_path="",
        python_packages={"demo": PythonPackage("demo", share, {"talker": "demo.talker"})},
    )


def ros_args(cmd: list[str]) -> list[str]:
    """What follows ``--ros-args`` on a node's command line."""
    return cmd[cmd.index("--ros-args") + 1 :]


def params_file(path: Path, *lines: str) -> Path:
    """A ROS params file at ``path`` giving every node (``/**``) the parameters ``lines``
    (``"rate: 5.0"``, written as they are)."""
    path.write_text("/**:\n  ros__parameters:\n" + "".join(f"    {line}\n" for line in lines))
    return path
