"""Fixtures for the stock node process tests: a private router, node processes, a probe node.

Every wait has a deadline and says what it waited for; every process started is stopped (its
whole process group) when the test ends.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest


def free_port() -> int:
    """A loopback TCP port nothing listens on right now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture
def router(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A router on a free loopback port, announced to children through LAUNCHKIT_ROUTER."""
    from launchkit.ros.router import start_router

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    handle = start_router(endpoint)
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    try:
        yield endpoint
    finally:
        handle.close()


class Processes:
    """Node processes of one test, each in its own process group."""

    def __init__(self) -> None:
        self.started: list[subprocess.Popen[str]] = []

    def start(self, module: str, *args: str) -> subprocess.Popen[str]:
        """Run ``python -m module args`` with output captured."""
        proc = subprocess.Popen(
            [sys.executable, "-m", module, *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
        )
        self.started.append(proc)
        return proc

    def stop_all(self) -> None:
        """SIGINT each group, SIGKILL what is left after a deadline."""
        for proc in self.started:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
        for proc in self.started:
            try:
                proc.communicate(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.communicate()


@pytest.fixture
def processes(router: str) -> Iterator[Processes]:
    """Start node processes; all of them are stopped after the test."""
    procs = Processes()
    try:
        yield procs
    finally:
        procs.stop_all()


@contextlib.contextmanager
def probe_node(name: str) -> Iterator[Any]:
    """A node ``name`` in the test process, on its own context, destroyed after the block."""
    import launchkit.ros as ros
    from launchkit.ros.context import Context

    context = Context()
    context.init([])
    node = ros.Node(name, context=context)
    try:
        yield node
    finally:
        node.destroy_node()
        context.shutdown()


@pytest.fixture
def probe(router: str) -> Iterator[Any]:
    """A node in the test process, on its own context, to publish and subscribe with."""
    with probe_node("stock_probe") as node:
        yield node


def spin_until(
    node: Any,
    predicate: Callable[[], bool],
    what: str,
    timeout: float = 15.0,
    each: Callable[[], None] | None = None,
) -> None:
    """Spin ``node`` until ``predicate()``; ``each`` runs every turn (to re-send a message)."""
    import launchkit.ros as ros

    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        if each is not None:
            each()
        ros.spin_once(node, timeout_sec=0.05)


def latched() -> Any:
    """Transient-local, reliable QoS of depth 1 (what /robot_description and /tf_static use)."""
    import launchkit.ros as ros

    return ros.QoSProfile(
        depth=1,
        reliability=ros.ReliabilityPolicy.RELIABLE,
        durability=ros.DurabilityPolicy.TRANSIENT_LOCAL,
    )
