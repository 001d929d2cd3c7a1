"""Fixtures for turtlesim's tests: a router and one turtlesim_node per module, and a probe node
in the test process that subscribes, publishes and calls services over the real transport.

Every wait has a deadline and says what it waited for; the node is stopped (its whole process
group) when the module's tests end, and each test starts from a ``/reset`` turtlesim.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from tests.stock.conftest import free_port, probe_node
from tests.stock.conftest import spin_until as stock_spin_until

NODE = "launchkit.stock.turtlesim.turtlesim_node"
DEADLINE = 20.0


class Program:
    """A program the test started (own process group); its output lines are kept as they come."""

    def __init__(self, argv: list[str], env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            argv,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
            env={**os.environ, **(env or {})},
        )
        self.out: list[str] = []
        self.err: list[str] = []
        self._pumps = [
            threading.Thread(target=self._pump, args=(self.proc.stdout, self.out), daemon=True),
            threading.Thread(target=self._pump, args=(self.proc.stderr, self.err), daemon=True),
        ]
        for pump in self._pumps:
            pump.start()

    @staticmethod
    def _pump(stream: Any, into: list[str]) -> None:
        for line in stream:
            into.append(line.rstrip("\n"))

    def mark(self) -> int:
        """Where the log (stderr) is now: :meth:`wait_log` looks after it."""
        return len(self.err)

    def wait_line(self, lines: list[str], text: str, after: int, what: str) -> str:
        """The first line of ``lines`` from ``after`` on containing ``text``."""
        deadline = time.monotonic() + DEADLINE
        while True:
            found = [line for line in lines[after:] if text in line]
            if found:
                return found[0]
            if time.monotonic() > deadline or self.proc.poll() is not None:
                raise AssertionError(
                    f"no {what} line containing {text!r} within {DEADLINE} s "
                    f"(exit {self.proc.poll()}); stdout: {self.out[-20:]}; stderr: {self.err[-20:]}"
                )
            time.sleep(0.02)

    def wait_log(self, text: str, after: int = 0) -> str:
        """The first log line (stderr) after ``after`` containing ``text``."""
        return self.wait_line(self.err, text, after, "log")

    def wait_out(self, text: str, after: int = 0) -> str:
        """The first stdout line after ``after`` containing ``text``."""
        return self.wait_line(self.out, text, after, "stdout")

    def stop(self) -> int:
        """SIGINT to the group, SIGKILL after a deadline; the exit status."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGINT)
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()
        for pump in self._pumps:
            pump.join(5)
        for stream in (self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()
        return self.proc.returncode


@pytest.fixture(scope="module")
def router(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """A router on a free loopback port, announced to children through LAUNCHKIT_ROUTER (and
    a log folder of the test run for what they start: ``launchkit run`` writes one)."""
    from launchkit.ros.router import start_router

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    handle = start_router(endpoint)
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("LAUNCHKIT_ROUTER", endpoint)
        patch.setenv("ROS_LOG_DIR", str(tmp_path_factory.mktemp("ros_log")))
        try:
            yield endpoint
        finally:
            handle.close()


@pytest.fixture(scope="module")
def programs(router: str) -> Iterator[Callable[..., Program]]:
    """Start programs (``python -m MODULE ...`` or any argv); all stopped after the module."""
    started: list[Program] = []

    def start(*argv: str, env: dict[str, str] | None = None) -> Program:
        program = Program(list(argv), env)
        started.append(program)
        return program

    try:
        yield start
    finally:
        for program in started:
            program.stop()


@pytest.fixture(scope="module")
def probe(router: str) -> Iterator[Any]:
    """A node in the test process, on its own context."""
    with probe_node("turtlesim_probe") as node:
        yield node


def spin_until(
    node: Any, predicate: Callable[[], bool], what: str, timeout: float = DEADLINE
) -> None:
    """Spin ``node`` until ``predicate()``; fail naming ``what`` after ``timeout`` s."""
    stock_spin_until(node, predicate, what, timeout)


def call(node: Any, srv_type: Any, service: str, /, **fields: Any) -> Any:
    """Call ``service`` with a request of ``fields``; its response."""
    client = node.create_client(srv_type, service)
    try:
        assert client.wait_for_service(timeout_sec=DEADLINE), f"service {service} not available"
        future = client.call_async(srv_type.Request(**fields))
        spin_until(node, future.done, f"the response of {service}")
        return future.result()
    finally:
        node.destroy_client(client)


def python(module: str, *args: str) -> list[str]:
    """The argv that runs ``python -m module args``."""
    return [sys.executable, "-m", module, *args]
