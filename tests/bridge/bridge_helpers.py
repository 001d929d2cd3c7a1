"""Helpers for the bridge's tests: a real rclpy peer, a launchkit peer, the bridge process.

Real rclpy uses Fast DDS: every test module gets its own ROS_DOMAIN_ID
(``launchkit.testing._isolation``) and ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` (Jazzy's
replacement of ``ROS_LOCALHOST_ONLY``), so DDS discovery stays on loopback and apart from other
test runs on the machine.
"""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
from collections.abc import Callable
from typing import Any

import launchkit.ros as ros
from tests.support import wait_until

DDS_ENV = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
RCLPY_MISSING = "the real rclpy is not installed: its wheels need CPython 3.11 on Linux x86_64"


class _SpunNode:
    """A node spun by an executor in a thread of its own (the peers below)."""

    node: Any

    def _spin_in_a_thread(self, executor: Any) -> None:
        self._executor = executor
        executor.add_node(self.node)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while not self._stop.is_set():
            self._executor.spin_once(timeout_sec=0.05)

    def _stop_spinning(self) -> None:
        self._stop.set()
        self._thread.join(timeout=5)

    def topics(self) -> dict[str, list[str]]:
        """The topics and types of the node's graph (its own included)."""
        return dict(self.node.get_topic_names_and_types())


class DdsPeer(_SpunNode):
    """A real rclpy node (Fast DDS) in the test process, spun in a thread."""

    def __init__(self, domain_id: int, name: str = "dds_peer") -> None:
        import rclpy
        from rclpy.executors import MultiThreadedExecutor
        from rclpy.signals import SignalHandlerOptions

        self.rclpy = rclpy
        self.context = rclpy.Context()
        rclpy.init(
            context=self.context,
            domain_id=domain_id,
            signal_handler_options=SignalHandlerOptions.NO,
        )
        self.node = rclpy.create_node(name, context=self.context)
        self._spin_in_a_thread(MultiThreadedExecutor(num_threads=2, context=self.context))

    def close(self) -> None:
        """Stop spinning and shut the rclpy context down."""
        self._stop_spinning()
        self._executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self.context.try_shutdown()


class LaunchkitPeer(_SpunNode):
    """A launchkit node on the test's router, spun in a thread."""

    def __init__(self, router: str, domain_id: int, name: str = "lk_peer") -> None:
        self.context = ros.Context(router=router)
        self.context.init([], domain_id)
        self.node = ros.Node(name, context=self.context)
        self._spin_in_a_thread(ros.SingleThreadedExecutor(context=self.context))

    def topics(self) -> dict[str, list[str]]:
        """launchkit's graph's topics and types (the node's own included)."""
        return dict(self.node.get_topic_names_and_types())

    def close(self) -> None:
        """Stop spinning and close the session."""
        self._stop_spinning()
        self.context.shutdown()


class BridgeProcess:
    """``launchkit bridge`` as a child process; its log lines are kept for the assertions."""

    def __init__(self, router: str, domain_id: int, *options: str) -> None:
        env = {**os.environ, **DDS_ENV, "ROS_DOMAIN_ID": str(domain_id)}
        env["RCUTILS_LOGGING_USE_STDOUT"] = "1"
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "launchkit", "bridge", "--router", router, *options],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=env,
        )
        self.lines: list[str] = []
        self._queue: queue.Queue[str] = queue.Queue()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))

    def wait_line(self, text: str, timeout: float = 30.0) -> str:
        """The first log line containing ``text``."""
        found: list[str] = []

        def seen() -> bool:
            found[:] = [line for line in self.lines if text in line]
            if not found and self.proc.poll() is not None:
                raise AssertionError(
                    f"the bridge exited ({self.proc.returncode}) before logging {text!r}:\n"
                    + "\n".join(self.lines[-30:])
                )
            return bool(found)

        wait_until(seen, timeout, f"the bridge to log {text!r}")
        return found[0]

    def stop(self) -> int:
        """SIGINT, then SIGKILL after 10 s; the exit status."""
        if self.proc.poll() is None:
            self.proc.send_signal(2)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._reader.join(5)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
        return self.proc.returncode


def any_of(items: list[Any], predicate: Callable[[Any], bool]) -> bool:
    """Whether any item satisfies ``predicate``."""
    return any(predicate(item) for item in items)
