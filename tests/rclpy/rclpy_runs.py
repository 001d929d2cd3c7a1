"""Running the small rclpy node files of ``nodes/`` twice: on the real rclpy (the ros-jazzy
wheels, over Fast DDS) and on launchkit's (the face first on ``PYTHONPATH``, over a router),
then comparing what they print.

A uniquely named module (not ``conftest``) so that the tests can import it.
"""

from __future__ import annotations

import importlib.util
import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from launchkit.envvars import RCLPY, ROUTER
from launchkit.ros import face
from launchkit.testing._isolation import domain_id

NODES = Path(__file__).parent / "nodes"
SCALE = float(os.environ.get("LAUNCHKIT_TIMEOUT_SCALE", "1"))
PATIENCE = 60.0 * SCALE  # a bound on waits that end on a condition (a busy machine)
REAL = "ros"
LAUNCHKIT = "launchkit"

real_rclpy = pytest.mark.skipif(
    sys.version_info[:2] != (3, 11) or importlib.util.find_spec("rclpy") is None,
    reason="the real rclpy (the ros-jazzy wheels) exists only for CPython 3.11 on Linux x86_64",
)


def environment(flavour: str, router: str, domain: int) -> dict[str, str]:
    """A node process's environment: the real rclpy over Fast DDS in ``domain``, or
    launchkit's (the face first on ``PYTHONPATH``) over ``router``."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", RCLPY)}
    env.update(
        ROS_DOMAIN_ID=str(domain),
        PYTHONUNBUFFERED="1",
        RCUTILS_COLORIZED_OUTPUT="0",
        PYTHONPATH=str(NODES),
    )
    env[RCLPY] = flavour
    if flavour == REAL:
        env["RMW_IMPLEMENTATION"] = "rmw_fastrtps_cpp"
    else:
        env[ROUTER] = router
        # the wheels' share/ (where installed): launchkit reads test_msgs from its files there
        env["AMENT_PREFIX_PATH"] = sys.prefix
        env.update(face.environment(env))
    return env


class DidNotEnd(AssertionError):
    """A node file's run did not end within :data:`PATIENCE`."""


class NodeRun:
    """One node file running; its output lines read with deadlines."""

    def __init__(self, name: str, env: dict[str, str], args: tuple[str, ...] = ()) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, str(NODES / name), *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
        )
        self.stdout: list[str] = []
        self.stderr: list[str] = []
        self._lines: queue.Queue[str] = queue.Queue()
        self._readers = [
            threading.Thread(target=self._pump, args=(self.proc.stdout, self.stdout), daemon=True),
            threading.Thread(target=self._pump, args=(self.proc.stderr, self.stderr), daemon=True),
        ]
        for reader in self._readers:
            reader.start()

    def _pump(self, stream: object, into: list[str]) -> None:
        for line in stream:  # type: ignore[attr-defined]
            into.append(line)
            self._lines.put(line)

    def expect(self, text: str) -> None:
        """Wait for a line (on either stream) containing ``text``."""
        deadline = time.monotonic() + PATIENCE
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(f"no line with {text!r}; so far: {self.stdout + self.stderr}")
            try:
                if text in self._lines.get(timeout=remaining):
                    return
            except queue.Empty:
                continue

    def wait_until_idle(self) -> None:
        """Wait until the main thread has been blocked for a while (its spin waiting for work):
        a signal sent then finds it waiting, not between two callbacks."""
        stat = Path(f"/proc/{self.proc.pid}/task/{self.proc.pid}/stat")
        deadline = time.monotonic() + PATIENCE
        asleep = 0
        while asleep < 10:
            if time.monotonic() > deadline:
                raise AssertionError(f"{self.proc.args} never waited: {self.stdout + self.stderr}")
            state = stat.read_text().rsplit(")", 1)[1].split()[0]
            asleep = asleep + 1 if state == "S" else 0
            time.sleep(0.02)

    def finish(self, stop: int | None = None) -> tuple[int, str, str]:
        """Stop it with ``stop`` (a signal) or wait for it to end; (status, stdout, stderr)."""
        if stop is not None and self.proc.poll() is None:
            self.proc.send_signal(stop)
        try:
            self.proc.wait(PATIENCE)
        except subprocess.TimeoutExpired:
            self.kill()
            raise DidNotEnd(f"{self.proc.args} did not end: {self.stdout + self.stderr}") from None
        self._close_streams()
        return (
            self.proc.returncode,
            normalize("".join(self.stdout)),
            normalize("".join(self.stderr)),
        )

    def kill(self) -> None:
        """Make sure it is gone."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        self._close_streams()

    def _close_streams(self) -> None:
        # closed here, not by the garbage collector in whichever test runs next (where an
        # unclosed file's ResourceWarning fails that test)
        for reader in self._readers:
            reader.join(10)
        for stream in (self.proc.stdout, self.proc.stderr):
            if stream is not None:
                stream.close()


def normalize(text: str) -> str:
    """Output with the log lines' timestamps (which always differ) replaced by ``T``."""
    return re.sub(r"\[\d+\.\d{9}\]", "[T]", text)


class Runs:
    """Starts node files of one flavour, each test on its own domain and router."""

    def __init__(self, flavour: str, router: str) -> None:
        self.flavour = flavour
        self.env = environment(flavour, router, domain_id())
        self.runs: list[NodeRun] = []

    def start(self, name: str, *args: str) -> NodeRun:
        """Run ``nodes/NAME`` with ``args``."""
        run = NodeRun(name, self.env, args)
        self.runs.append(run)
        return run

    def close(self) -> None:
        """Kill whatever still runs."""
        for run in self.runs:
            run.kill()


def scenario_output(
    make: Callable[[str], Runs], flavour: str, scenario: Callable[[Runs], str]
) -> str:
    """What ``scenario`` prints on ``flavour`` (``make`` is the ``runs`` fixture).

    The real rclpy gets a second try, on a fresh domain, when one of its processes hangs: under
    load its action client over Fast DDS now and then never receives a result the server has
    sent (the server logs the goal's success; the client waits in
    ``spin_until_future_complete`` for good). That race is upstream's, not what these tests
    measure. launchkit's runs get no second try.
    """
    try:
        return scenario(make(flavour))
    except DidNotEnd:
        if flavour != REAL:
            raise
    return scenario(make(flavour))


__all__ = [
    "LAUNCHKIT",
    "REAL",
    "DidNotEnd",
    "NodeRun",
    "Runs",
    "normalize",
    "real_rclpy",
    "scenario_output",
    "signal",
]
