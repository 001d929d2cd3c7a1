"""Drive the ``launchkit`` command line from a test: start it in its own session, follow its
output line by line, signal it, and check that every process it reported is gone.

The engine's own process tests use this directly because they test what sits under the pytest
plugin (signals to the launcher itself, SIGKILL of the launcher); everything else uses
``launchkit.testing``.
"""

from __future__ import annotations

import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

STARTED = re.compile(r"\[INFO\] \[(?P<name>[^\]]+)\]: process started with pid \[(?P<pid>\d+)\]")


class Launcher:
    """One ``launchkit run`` process and everything it printed so far."""

    def __init__(self, *args: str, cwd: Path, env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "launchkit", "run", *args],
            cwd=cwd,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            text=True,
            start_new_session=True,
            env={**os.environ, **(env or {})},
        )
        self.lines: list[str] = []
        self._queue: queue.Queue[str | None] = queue.Queue()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        self.pids: dict[str, int] = {}

    def _read(self) -> None:
        assert self.proc.stdout is not None
        try:
            for line in self.proc.stdout:
                self._queue.put(line.rstrip("\n"))
        except (OSError, ValueError):
            pass  # closed under us by close() after a failed test
        self._queue.put(None)

    def _take(self, timeout: float) -> str | None:
        line = self._queue.get(timeout=timeout)
        if line is not None:
            self.lines.append(line)
            match = STARTED.search(line)
            if match:
                self.pids[match["name"]] = int(match["pid"])
        return line

    def wait_line(self, pattern: str, timeout: float = 20.0, count: int = 1) -> str:
        """The ``count``-th line printed so far that contains ``pattern``, waiting for it up to
        ``timeout`` seconds; fails with the whole output."""
        deadline = time.monotonic() + timeout
        while True:
            matches = [line for line in self.lines if pattern in line]
            if len(matches) >= count:
                return matches[count - 1]
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(f"no line with {pattern!r} within {timeout} s:\n{self.text}")
            try:
                if self._take(remaining) is None:
                    raise AssertionError(
                        f"launchkit exited before printing {pattern!r}:\n{self.text}"
                    )
            except queue.Empty:
                pass

    def signal(self, signum: int) -> None:
        """Send ``signum`` to the launcher process alone."""
        self.proc.send_signal(signum)

    def ctrl_c(self) -> None:
        """SIGINT to the launcher's process group, as Ctrl-C at its terminal sends it (to the
        launcher and to the helpers it keeps in its group; each node leads a session of its
        own)."""
        os.killpg(self.proc.pid, signal.SIGINT)

    def finish(self, timeout: float = 30.0) -> int:
        """Wait for the launcher to exit and read the rest of its output; its exit status."""
        try:
            status = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(
                f"launchkit did not exit within {timeout} s:\n{self.text}"
            ) from None
        while True:
            try:
                if self._take(5.0) is None:
                    break
            except queue.Empty:
                break
        self.close()
        return status

    def close(self) -> None:
        """Release the output pipe once the reader has seen its end."""
        self._reader.join(10)
        if self.proc.stdout is not None:
            self.proc.stdout.close()

    def kill(self) -> None:
        """Last-resort cleanup: SIGKILL the launcher's session and every reported process."""
        for pid in [self.proc.pid, *self.pids.values()]:
            try:
                os.killpg(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        self.proc.wait(5)
        self.close()

    @property
    def text(self) -> str:
        """Everything printed so far."""
        return "\n".join(self.lines)


def alive(pid: int) -> bool:
    """Whether ``pid`` exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def wait_gone(pids: list[int], timeout: float = 10.0) -> None:
    """Fail unless every pid has exited within ``timeout``."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        left = [pid for pid in pids if alive(pid)]
        if not left:
            return
        time.sleep(0.02)
    left = [pid for pid in pids if alive(pid)]
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    raise AssertionError(f"processes {left} survived (killed now)")


def run_launchkit(
    *args: str, cwd: Path, env: dict[str, str] | None = None, stdin: str | None = None
) -> subprocess.CompletedProcess[str]:
    """Run the launchkit command line to completion (``stdin`` its input); its output
    captured."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
        env={**os.environ, **(env or {})},
        input=stdin,
    )


def executable(name: str, code: str, **attrs: str) -> str:
    """An ``<executable>`` element running Python ``code``, its output on the screen."""
    extra = " ".join(f'{k}="{v}"' for k, v in attrs.items())
    # The code goes inside a single-quoted shell word: its own quotes become double quotes.
    escaped = code.replace("'", '"').replace("&", "&amp;").replace('"', "&quot;")
    return (
        f'<executable name="{name}" output="screen" {extra} '
        f"cmd=\"{sys.executable} -c '{escaped}'\"/>"
    )


def run_rejected(path: Path, prologue: str, body: str) -> tuple[str, str]:
    """Write ``prologue`` and ``body`` to ``path`` (``{marker}`` in the prologue names a file that
    a process it starts makes) and run ``launchkit run`` on it, which must refuse the file: exit
    status 2, no traceback, nothing started. Its first line on stderr, and the whole of stderr."""
    marker = path.parent / "started"
    path.write_text(prologue.format(marker=marker) + body)
    result = run_launchkit("run", str(path), cwd=path.parent)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr + result.stdout
    assert not marker.exists(), "a process started although the file is bad"
    return result.stderr.splitlines()[0], result.stderr
