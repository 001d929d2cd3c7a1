"""Helpers for the bag tests: a router per test, ``launchkit bag`` processes, probe nodes,
message samples filled from the type definitions, and waits with deadlines."""

from __future__ import annotations

import array
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

import launchkit.ros as ros
from launchkit.ros.message_data import fields_of
from launchkit.ros.msgs import get_message, is_message

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
_INT_RANGES = {
    "int8": (-128, 127),
    "uint8": (0, 255),
    "byte": (0, 127),  # rosbags packs byte signed
    "char": (0, 255),
    "int16": (-32768, 32767),
    "uint16": (0, 65535),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}


def free_port() -> int:
    """A loopback TCP port nothing listens on right now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def wait_for(predicate: Callable[[], bool], timeout: float, what: str) -> None:
    """Poll ``predicate`` until it holds; fail naming ``what`` after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(0.02)


def launchkit_env(router: str) -> dict[str, str]:
    """The environment of a ``launchkit`` child on ``router`` (its venv's bin on the PATH)."""
    path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"
    return {**os.environ, "LAUNCHKIT_ROUTER": router, "PATH": path}


def run_bag(*args: str, router: str = "", timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit bag ARGS`` to completion (stdin not a terminal)."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", "bag", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        stdin=subprocess.DEVNULL,
        env=launchkit_env(router) if router else None,
    )


class BagProcess:
    """A ``launchkit bag ...`` process in its own group; its output is collected."""

    def __init__(self, router: str, *args: str) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "launchkit", "bag", *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=launchkit_env(router),
            start_new_session=True,
        )
        self.lines: list[str] = []
        self._reader = threading.Thread(target=self._pump, daemon=True)
        self._reader.start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))

    @property
    def output(self) -> str:
        """Everything printed so far."""
        return "\n".join(self.lines)

    def wait_line(self, text: str, timeout: float = 20) -> None:
        """Wait for a line containing ``text`` (fails early if the process exits)."""
        wait_for(
            lambda: any(text in line for line in self.lines) or self.proc.poll() is not None,
            timeout,
            f"a line with {text!r} from launchkit bag; output:\n{self.output}",
        )
        assert any(text in line for line in self.lines), (
            f"launchkit bag exited {self.proc.returncode} before printing {text!r}:\n{self.output}"
        )

    def interrupt(self, timeout: float = 30) -> int:
        """SIGINT (Ctrl-C) and wait for the exit status."""
        self.proc.send_signal(signal.SIGINT)
        return self.wait(timeout)

    def wait(self, timeout: float = 60) -> int:
        """Wait for the exit status (the output is complete then)."""
        code = self.proc.wait(timeout)
        self._finish()
        return code

    def _finish(self) -> None:
        self._reader.join(5)
        if self.proc.stdout is not None and not self._reader.is_alive():
            self.proc.stdout.close()

    def kill(self) -> None:
        """SIGKILL the whole group (no cleanup at all)."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait(10)
        self._finish()


@contextmanager
def bag_process(router: str, *args: str) -> Iterator[BagProcess]:
    """A :class:`BagProcess` that is killed when the block ends, whatever happened."""
    process = BagProcess(router, *args)
    try:
        yield process
    finally:
        process.kill()


class Probe:
    """A node of the test process with its own context, spun by a thread."""

    def __init__(self, router: str, name: str = "bag_probe", **node_args: Any) -> None:
        self.context = ros.Context(router=router)
        self.context.init([])
        self.node = ros.Node(
            name, context=self.context, start_parameter_services=False, **node_args
        )
        self._stop = threading.Event()
        self._spinner = threading.Thread(target=self._spin, daemon=True)
        self._spinner.start()

    def _spin(self) -> None:
        while not self._stop.is_set():
            ros.spin_once(self.node, timeout_sec=0.05)

    def close(self) -> None:
        """Stop spinning and close the session."""
        self._stop.set()
        self._spinner.join(5)
        self.context.shutdown()


@contextmanager
def probe(router: str, name: str = "bag_probe", **node_args: Any) -> Iterator[Probe]:
    """A :class:`Probe` closed after the block."""
    node = Probe(router, name, **node_args)
    try:
        yield node
    finally:
        node.close()


def sample(type_name: str, seed: int = 1) -> Any:
    """A message of ``type_name`` with every field set to a value other than its default."""
    fields = fields_of(type_name)
    cls = get_message(type_name)
    values = {name: _value(desc, seed + i) for i, (name, desc) in enumerate(fields)}
    return cls(**values)


def _value(desc: Any, seed: int) -> Any:
    kind, detail = desc
    if kind == _BASE:
        return _base(detail[0], detail[1], seed)
    if kind == _NAME:
        return sample(detail, seed)
    sub, length = detail
    count = length if kind == _ARRAY else min(length or 2, 2)
    return [_value(sub, seed + i) for i in range(count)]


def _base(name: str, bound: int, seed: int) -> Any:
    if name in ("string", "wstring"):
        text = f"s{seed}"
        return text[:bound] if bound else text
    if name == "bool":
        return True
    if name == "byte":
        return bytes([seed % 128])
    if name in ("float32", "float64"):
        return 0.5 + seed * 0.25  # exact in float32
    low, high = _INT_RANGES[name]
    return low + (seed * 37 + 3) % (high - low)


def same(a: Any, b: Any) -> bool:
    """Field-by-field equality of decoded messages (arrays compared by value, element by
    element: a message's own ``==`` is rosidl's, which calls fixed-size arrays equal unless
    every element differs)."""
    if isinstance(a, (np.ndarray, array.array)) or isinstance(b, (np.ndarray, array.array)):
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    if is_message(a):
        return type(a) is type(b) and all(
            same(getattr(a, f), getattr(b, f)) for f in a.get_fields_and_field_types()
        )
    return bool(a == b)
