"""Helpers for the ROS layer's tests: child node processes, spinning with deadlines.

A uniquely named module (not ``conftest``) so that tests can import it whatever other
``conftest.py`` files the suite has.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

from launchkit.ros import Node, spin_once
from tests.support import KeptLines, OutputLines, ament_package

NODES_DIR = Path(__file__).parent / "nodes"


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
        assert self.proc.stdout is not None
        self.out = OutputLines(self.proc.stdout)
        assert self.proc.stderr is not None
        self.err = KeptLines(self.proc.stderr)

    @property
    def stderr(self) -> str:
        """What it wrote on stderr so far."""
        return self.err.text

    def expect(self, predicate: str, timeout: float = 10.0) -> str:
        """The next stdout line containing ``predicate``; fails after ``timeout`` seconds."""
        return self.out.expect(
            predicate, timeout, lambda: f"exit={self.proc.poll()} stderr={self.stderr[-2000:]}"
        )

    def stop(self, timeout: float = 5.0) -> int:
        """SIGINT, then SIGKILL after ``timeout``; the exit status."""
        if self.proc.poll() is None:
            self.proc.send_signal(2)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.out.join()
        self.err.join()
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
    run = f"#!{sys.executable}\nimport runpy\nrunpy.run_path({{!r}}, run_name='__main__')\n"
    names = ("talker", "listener", "knobs")
    ament_package(
        prefix, "demo", {name: run.format(str(NODES_DIR / f"{name}.py")) for name in names}
    )


def stderr_line(child: Child, text: str, timeout: float) -> str:
    """The first stderr line of ``child`` containing ``text``; fails after ``timeout`` s."""
    line = child.err.first(text, timeout, ended=lambda: child.proc.poll() is not None)
    if line is None:
        raise AssertionError(
            f"no stderr line containing {text!r} within {timeout} s; "
            f"exit={child.proc.poll()} stderr={child.stderr[-2000:]}"
        )
    return line
