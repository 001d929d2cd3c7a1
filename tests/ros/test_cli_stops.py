"""Every long-running command stops promptly on Ctrl-C, even with every core busy (issue #9).

The commands run at once; once each has said it is running, processes that keep every core busy
start, then all commands get SIGINT together and each must exit, with status 0, before a
deadline twice the one-second target (``LAUNCHKIT_TIMEOUT_SCALE`` scales it). Nothing else is
timed. (The cores are busy from the stop on, not while the commands start: starting six Python
processes on saturated cores took most of the test's half minute and tested nothing.)
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator

import pytest
from ros_helpers import NODES_DIR, Child

from launchkit.testing._deadline import Deadline, scaled
from launchkit.testing._isolation import free_loopback_port

STOP_DEADLINE = 2.0  # seconds from SIGINT to exit; the target is 1 s
URDF = "robot_description:=<robot name='r'><link name='a'/></robot>"

# name: (launchkit arguments, a line it prints once it runs)
COMMANDS = {
    "topic echo": (["topic", "echo", "/chatter"], "data: hello"),
    "topic hz": (["topic", "hz", "/chatter"], "average rate"),
    "topic pub": (["topic", "pub", "/x", "std_msgs/msg/String", "{data: a}", "-r", "20"], "#2"),
    "router": (["router", "--router", "tcp/127.0.0.1:{port}"], "listening"),
    "exec robot_state_publisher": (
        ["exec", "robot_state_publisher", "robot_state_publisher", "--ros-args", "-p", URDF],
        "publishing robot 'r'",
    ),
}


@pytest.fixture
def busy_cores() -> Iterator[Callable[[], None]]:
    """Call it to start processes spinning on every core; they spin until the test ends."""
    hogs: list[subprocess.Popen[bytes]] = []

    def start() -> None:
        spin = [sys.executable, "-c", "while 1: pass"]
        hogs.extend(subprocess.Popen(spin) for _ in range(os.cpu_count() or 2))

    try:
        yield start
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()


def test_every_long_running_command_stops_promptly_under_load(
    router: str, children: list[Child], busy_cores: Callable[[], None]
) -> None:
    talker = Child([str(NODES_DIR / "talker.py")])
    children.append(talker)
    talker.expect("talker ready", timeout=scaled(30))
    running: dict[str, Child] = {}
    for name, (args, _) in COMMANDS.items():
        argv = [arg.replace("{port}", str(free_loopback_port())) for arg in args]
        # node loggers write to stderr; the helper reads stdout
        child = Child(["-m", "launchkit", *argv], env={"RCUTILS_LOGGING_USE_STDOUT": "1"})
        children.append(child)
        running[name] = child
    for name, child in running.items():
        child.expect(COMMANDS[name][1], timeout=scaled(60))

    busy_cores()
    for child in running.values():
        child.proc.send_signal(signal.SIGINT)
    sent = time.monotonic()
    deadline = Deadline(STOP_DEADLINE)
    late: list[str] = []
    for name, child in running.items():
        try:
            status = child.proc.wait(timeout=deadline.remaining())
        except subprocess.TimeoutExpired:
            late.append(name)
            continue
        assert status == 0, f"{name} exited with {status}: {child.stderr[-2000:]}"
    waited = time.monotonic() - sent
    assert not late, f"still running {waited:.1f} s after SIGINT: {', '.join(late)}"
