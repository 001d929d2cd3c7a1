"""A timer counts from when the processes started beside it are running, as in Jazzy, so its
output never comes before theirs merely because launchkit was slow to start them (a busy
machine, a ``$(command)`` later in the same file, the router starting for the first node).

Checked beside a process that burns a CPU, with a file whose evaluation takes longer than the
timer's period. Expectation from the real launch (``ros2_launch.py`` of the reference tools:
launch 3.4.3, launch_ros 0.26.6), which starts a timer's clock when its event loop regains
control: after the pass that set it, with the processes of that pass.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.compat.conftest import run_launch, stub_prefix

ORDER = """\
<launch>
  <node pkg="demo" exec="talker" name="talker" output="screen"/>
  <timer period="0.5">
    <log message="timer fired"/>
  </timer>
  <executable cmd="echo $(command 'sleep 0.8')slow" output="screen"/>
</launch>
"""

TALKER = '#!/bin/sh\necho "talker up"\nsleep 1\necho "talker done"\n'


@pytest.fixture
def busy_cpu() -> Iterator[None]:
    """A process burning a CPU for the duration of the test."""
    burner = subprocess.Popen([sys.executable, "-c", "while True: pass"], start_new_session=True)
    try:
        yield
    finally:
        os.killpg(burner.pid, signal.SIGKILL)
        burner.wait()


@pytest.mark.usefixtures("busy_cpu")
def test_a_timer_beside_a_node_fires_after_the_nodes_first_lines(launch_dir: Path) -> None:
    # `ros2 launch order.launch.xml` (reference runs 2026-11-29, twice): "process started" of
    # talker-1 and echo-2, then "[talker-1] talker up" and "[echo-2] slow" (in either order,
    # with echo-2's exit), then "[INFO] [launch.user]: timer fired", then "[talker-1] talker
    # done"
    prefix = stub_prefix(launch_dir / "prefix", {"demo": []})
    talker = prefix / "lib" / "demo" / "talker"
    talker.parent.mkdir(parents=True)
    talker.write_text(TALKER)
    talker.chmod(0o755)
    (launch_dir / "order.launch.xml").write_text(ORDER)
    for _ in range(3):
        ran = run_launch(launch_dir, "order.launch.xml", env={"AMENT_PREFIX_PATH": str(prefix)})
        assert ran.status == 0, ran.text
        lines = ran.launch_lines()
        timer = lines.index("[INFO] [launch.user]: timer fired")
        assert lines.index("[talker-1] talker up") < timer, ran.text
        assert lines.index("[echo-2] slow") < timer, ran.text
        assert timer < lines.index("[talker-1] talker done"), ran.text
