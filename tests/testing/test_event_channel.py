"""The engine's side of the plugin: ``launchkit run --events-fd`` streams the launch's life
as JSON lines, and stops the launch when the test process's end of the channel closes."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

from launchkit.testing import _procscan
from launchkit.testing._deadline import Deadline, scaled
from tests.testing.conftest import LAUNCH_DIR


class Channel:
    """A launcher started with an event channel, and the events read so far."""

    def __init__(self, path: Path, tmp_path: Path) -> None:
        self.ours, theirs = socket.socketpair()
        self.ours.settimeout(scaled(10))  # a deadline on every read
        fd = str(theirs.fileno())
        self.process = subprocess.Popen(
            [sys.executable, "-m", "launchkit", "run", "--events-fd", fd, str(path)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            stdin=subprocess.DEVNULL,
            pass_fds=[theirs.fileno()],
            start_new_session=True,
            env={**os.environ, "ROS_LOG_DIR": str(tmp_path)},
        )
        theirs.close()
        self.stream = self.ours.makefile("rb")
        self.events: list[dict[str, object]] = []

    def read_until(self, kind: str) -> dict[str, object]:
        """Read events until one of ``kind`` (a socket timeout fails the test)."""
        for line in self.stream:
            event = json.loads(line)
            self.events.append(event)
            if event["event"] == kind:
                return event
        raise AssertionError(f"the channel closed before a {kind!r} event: {self.events}")

    def close(self) -> None:
        """Close our end; end the launcher if it still runs."""
        self.stream.close()
        self.ours.close()
        if self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
        self.process.wait()


def test_the_launch_is_streamed_as_events(tmp_path):
    channel = Channel(LAUNCH_DIR / "required_arg.launch.xml", tmp_path)
    try:
        failed = channel.read_until("failed")
        assert "required argument 'speed'" in str(failed["message"])
        assert channel.process.wait(timeout=scaled(10)) == 2
    finally:
        channel.close()

    channel = Channel(LAUNCH_DIR / "crash.launch.xml", tmp_path)
    try:
        started = channel.read_until("started")
        assert started["process"] == "steady-1" and started["name"] == "steady"
        assert isinstance(started["pid"], int) and started["node"] is None
        assert channel.read_until("ready") == {"event": "ready"}
        exited = channel.read_until("exited")
        assert exited["process"] == "crasher-2" and exited["returncode"] == 3
        outputs = [e for e in channel.events if e["event"] == "output"]
        assert {"event": "output", "process": "crasher-2", "stream": "stdout",
                "text": "crashing"} in outputs  # fmt: skip
    finally:
        channel.close()


def test_the_launch_stops_when_the_test_process_goes_away(tmp_path):
    channel = Channel(LAUNCH_DIR / "talker.launch.xml", tmp_path)
    try:
        channel.read_until("ready")
        pids = [int(str(e["pid"])) for e in channel.events if e["event"] == "started"]
        channel.stream.close()
        channel.ours.close()  # as if the test process had died
        # a clean shutdown, started by the SIGTERM the launcher sends itself: 128 + 15
        assert channel.process.wait(timeout=scaled(30)) == 143
        assert _procscan.wait_gone(_procscan.members(pids), Deadline(5)) == []
    finally:
        channel.close()


def test_a_bad_events_fd_is_a_user_error(tmp_path):
    talker = str(LAUNCH_DIR / "talker.launch.xml")
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "run", "--events-fd", "999", talker],
        capture_output=True,
        text=True,
        timeout=scaled(30),
        check=False,
        env={**os.environ, "ROS_LOG_DIR": str(tmp_path)},
    )
    assert done.returncode == 2
    assert done.stderr.startswith("error: --events-fd 999: Bad file descriptor")
    assert "Traceback" not in done.stderr
