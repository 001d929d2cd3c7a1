"""No pip left behind: `launchkit build` stopped by Ctrl-C, or killed, takes the pip it runs
(and pip's own children, such as the setup.py it runs) with it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from workspaces import environment, python_package, write_package

DEADLINE = 60.0
# a setup.py that says it runs, then takes its time (a slow build)
SLOW_SETUP = """\
import pathlib, time
pathlib.Path({marker!r}).write_text("started")
time.sleep(300)
"""


def _processes_mentioning(text: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except OSError:
            continue
        if text in cmdline:
            found.append(int(entry.name))
    return found


def _wait(condition: object, what: str) -> None:
    deadline = time.monotonic() + DEADLINE
    while not condition():  # type: ignore[operator]
        assert time.monotonic() < deadline, f"waited {DEADLINE}s for {what}"
        time.sleep(0.05)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGKILL])
def test_stopping_the_build_stops_pip(tmp_path: Path, signum: int) -> None:
    root = tmp_path / "ws"
    marker = tmp_path / "setup-started"
    files = python_package("slow_py", {"run": "def main():\n    pass\n"})
    files["setup.py"] = SLOW_SETUP.format(marker=str(marker)) + files["setup.py"]
    write_package(root / "src", "slow_py", files)
    build = subprocess.Popen(
        [sys.executable, "-m", "launchkit", "build"],
        cwd=root,
        env=environment(tmp_path),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        _wait(marker.exists, "setup.py to start under pip")
        assert _processes_mentioning(str(root)), "pip runs in the workspace"
        build.send_signal(signum)
        status = build.wait(DEADLINE)
        assert status == (130 if signum == signal.SIGINT else -signal.SIGKILL)
        _wait(lambda: not _processes_mentioning(str(root)), "pip and setup.py to end")
    finally:
        if build.poll() is None:
            build.kill()
            build.wait()
        for pid in _processes_mentioning(str(root)):  # what a failing run left behind
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
