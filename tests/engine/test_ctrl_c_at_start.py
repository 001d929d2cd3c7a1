"""Ctrl-C in the first second of the seed launch, while its nodes are still importing (issue
#25, point 6): every node ends within its usual time (no 5 s wait for the SIGTERM), cleanly
(no ``KeyboardInterrupt`` traceback), and the launch exits 0, as ``ros2 launch`` after Ctrl-C.

The signal goes right after the K-th ``process started`` line, on a machine kept busy by a
spinning process for the whole test.
"""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from launchkit.testing._isolation import domain_id, free_loopback_port, router_endpoint
from tests.engine.launcher import Launcher, wait_gone

#: The seed launch's processes: gzserver, spawn_entity.py, robot_state_publisher, rviz2.
PROCESSES = 4


@pytest.fixture(scope="module")
def busy_machine() -> Iterator[None]:
    """One core kept busy while the module's tests run (the load of a developer's machine)."""
    spinner = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        yield
    finally:
        spinner.kill()
        spinner.wait()


@pytest.mark.parametrize("after", range(1, PROCESSES + 1))
def test_ctrl_c_while_the_seed_launch_starts(
    tmp_path: Path, busy_machine: None, after: int
) -> None:
    env = {
        "LAUNCHKIT_ROUTER": router_endpoint(free_loopback_port()),
        "LAUNCHKIT_VIEWER_PORT": str(free_loopback_port()),
        "ROS_DOMAIN_ID": str(domain_id()),
        "ROS_LOG_DIR": str(tmp_path),
    }
    launcher = Launcher("robot_wheel", "gazebo_and_rviz.launch.xml", cwd=tmp_path, env=env)
    try:
        launcher.wait_line("process started with pid", timeout=60, count=after)
        launcher.ctrl_c()
        interrupted = time.monotonic()
        status = launcher.finish(timeout=60)
        took = time.monotonic() - interrupted
    finally:
        if launcher.proc.poll() is None:
            launcher.kill()
    text = launcher.text
    assert status == 0, text
    assert "Traceback" not in text and "KeyboardInterrupt" not in text, text
    assert "escalating to 'SIGTERM'" not in text, f"a starting node waited out SIGINT:\n{text}"
    assert "process has died" not in text, text
    assert took < 5.0, f"{took:.1f} s to stop:\n{text}"
    wait_gone(list(launcher.pids.values()))
