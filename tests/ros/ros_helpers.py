"""Helpers for the ROS layer's tests: free ports, child node processes, spinning with deadlines.

A uniquely named module (not ``conftest``) so that tests can import it whatever other
``conftest.py`` files the suite has.
"""

from __future__ import annotations

import os
import queue
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from launchkit.ros import Node, spin_once

NODES_DIR = Path(__file__).parent / "nodes"


def free_port() -> int:
    """A TCP port on loopback that nothing listens on right now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class Child:
    """A node process started by a test; its stdout lines are read with deadlines."""

    def __init__(self, args: list[str], env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, **(env or {})},
        )
        self.lines: queue.Queue[str] = queue.Queue()
        self.stderr: list[str] = []
        self._threads = [
            threading.Thread(target=self._pump, daemon=True),
            threading.Thread(target=self._pump_err, daemon=True),
        ]
        for thread in self._threads:
            thread.start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))

    def _pump_err(self) -> None:
        assert self.proc.stderr is not None
        for line in self.proc.stderr:
            self.stderr.append(line)

    def expect(self, predicate: str, timeout: float = 10.0) -> str:
        """The first stdout line containing ``predicate``; fails after ``timeout`` seconds."""
        deadline = time.monotonic() + timeout
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(
                    f"no line containing {predicate!r} within {timeout} s; "
                    f"exit={self.proc.poll()} stderr={''.join(self.stderr)[-2000:]}"
                )
            try:
                line = self.lines.get(timeout=remaining)
            except queue.Empty:
                continue
            if predicate in line:
                return line

    def stop(self, timeout: float = 5.0) -> int:
        """SIGINT, then SIGKILL after ``timeout``; the exit status."""
        if self.proc.poll() is None:
            self.proc.send_signal(2)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        for thread in self._threads:
            thread.join(timeout=5)
        for stream in (self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()
        return self.proc.returncode


def spin_until(node: Node, predicate: Callable[[], bool], timeout: float, what: str) -> None:
    """Spin ``node`` until ``predicate()`` holds; fail naming ``what`` after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        spin_once(node, timeout_sec=0.05)


def demo_package(prefix: Path) -> None:
    """An AMENT_PREFIX_PATH package ``demo`` whose executables run the test nodes (``talker``,
    ``listener``, ``knobs``): what ``launchkit exec demo talker`` and a launch's ``<node>``
    start."""
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / "demo"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    (prefix / "share" / "demo").mkdir(parents=True)
    lib = prefix / "lib" / "demo"
    lib.mkdir(parents=True)
    for name in ("talker", "listener", "knobs"):
        exe = lib / name
        script = str(NODES_DIR / f"{name}.py")
        exe.write_text(
            f"#!{sys.executable}\nimport runpy\nrunpy.run_path({script!r}, run_name='__main__')\n"
        )
        exe.chmod(0o755)


def stderr_line(child: Child, text: str, timeout: float) -> str:
    """The first stderr line of ``child`` containing ``text``; fails after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while True:
        found = [line for line in list(child.stderr) if text in line]
        if found:
            return found[0]
        if time.monotonic() > deadline or child.proc.poll() is not None:
            raise AssertionError(
                f"no stderr line containing {text!r} within {timeout} s; "
                f"exit={child.proc.poll()} stderr={''.join(child.stderr)[-2000:]}"
            )
        time.sleep(0.02)
