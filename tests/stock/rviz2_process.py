"""An rviz2 process on a private router, for tests: where it serves and what it printed."""

from __future__ import annotations

import http.client
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

from launchkit.testing._isolation import free_loopback_port

DEADLINE = 20.0


class Rviz2:
    """The rviz2 process of the module, where it serves, and its output lines."""

    def __init__(self, proc: subprocess.Popen[str], port: int) -> None:
        self.proc = proc
        self.port = port
        self.lines: list[str] = []
        self.changed = threading.Condition()
        self.ws = f"ws://127.0.0.1:{port}"

    def read(self) -> None:
        """Collect the process's output (in a thread of its own)."""
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            with self.changed:
                self.lines.append(line)
                self.changed.notify_all()

    def wait_line(self, text: str) -> str:
        """The first output line containing ``text``, waiting for it up to the deadline."""
        with self.changed:
            found = self.changed.wait_for(
                lambda: next((line for line in self.lines if text in line), None), DEADLINE
            )
        assert found, f"rviz2 did not print {text!r} within {DEADLINE} s: {self.lines}"
        return found

    def get(self, path: str, host: str | None = None) -> tuple[int, dict[str, str], bytes]:
        """``GET path``: status, headers, body."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=10)
        try:
            connection.putrequest("GET", path, skip_host=host is not None)
            if host is not None:
                connection.putheader("Host", host)
            connection.endheaders()
            response = connection.getresponse()
            return response.status, dict(response.getheaders()), response.read()
        finally:
            connection.close()


@contextmanager
def running_rviz2(router: str, *args: str, env: dict[str, str] | None = None) -> Iterator[Rviz2]:
    """rviz2 with ``args`` (and ``env`` added to the environment) on a free port, serving once
    this yields; stopped (its whole process group) afterwards."""
    port = free_loopback_port()
    env = {**os.environ, "LAUNCHKIT_ROUTER": router, **(env or {})}
    env.pop("LAUNCHKIT_SUPERVISOR_SOCKET", None)  # print the viewer line itself
    proc = subprocess.Popen(
        [sys.executable, "-m", "launchkit.stock.rviz2.node", "--port", str(port), *args],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
        start_new_session=True,
    )
    rviz2 = Rviz2(proc, port)
    reader = threading.Thread(target=rviz2.read, daemon=True)
    reader.start()
    try:
        rviz2.wait_line("viewer: http://")
        yield rviz2
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        reader.join(5)
        assert proc.stdout is not None
        proc.stdout.close()
