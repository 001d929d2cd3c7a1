"""Fixtures for the engine tests that drive ``launchkit run`` directly (see launcher.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.engine.launcher import Launcher, wait_gone


def write(tmp_path: Path, body: str, name: str = "t.launch.xml") -> Path:
    """A launch file with ``body`` inside ``<launch>``."""
    path = tmp_path / name
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


@pytest.fixture
def run(tmp_path: Path):  # type: ignore[no-untyped-def]
    """Start ``launchkit run`` on a launch file body; everything is killed at the end."""
    started: list[Launcher] = []

    def start(body: str, *args: str) -> Launcher:
        launcher = Launcher(
            str(write(tmp_path, body)), *args, cwd=tmp_path, env={"ROS_LOG_DIR": str(tmp_path)}
        )
        started.append(launcher)
        return launcher

    yield start
    for launcher in started:
        if launcher.proc.poll() is None:
            launcher.kill()
        launcher.close()
        wait_gone(list(launcher.pids.values()))
