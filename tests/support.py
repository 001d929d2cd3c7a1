"""Helpers shared by tests of several folders: a router hosted by the test process, a poll
with a deadline for conditions that no event announces, the output lines of a child process
read as they come (taken one by one, or kept), ROS-style packages in an install prefix, and the
processes a test's ``sleep MARKER`` commands started.

(``launchkit.testing._isolation`` has the free loopback port and the router endpoint for it.)
"""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import IO

from launchkit.testing._isolation import free_loopback_port, router_endpoint


@contextmanager
def hosted_router() -> Iterator[str]:
    """A Zenoh router hosted by this process on a free loopback port; its endpoint."""
    from launchkit.ros.router import start_router  # zenoh: only for the tests that need it

    endpoint = router_endpoint(free_loopback_port())
    handle = start_router(endpoint)
    assert handle.hosted, f"another router already listens at {endpoint}"
    try:
        yield endpoint
    finally:
        handle.close()


def wait_until(
    predicate: Callable[[], bool], timeout: float, what: str, *, every: float = 0.02
) -> None:
    """Poll ``predicate`` every ``every`` seconds until it holds; fail naming ``what`` after
    ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(every)


class _LineReader:
    """A thread that reads a child's output stream line by line (newline stripped) as the lines
    come, and hands each to :meth:`_arrived` (the two kinds of reading below)."""

    def __init__(self, stream: IO[str]) -> None:
        self._reader = threading.Thread(target=self._pump, args=(stream,), daemon=True)
        self._reader.start()

    def _pump(self, stream: IO[str]) -> None:
        try:
            for line in stream:
                self._arrived(line.rstrip("\n"))
        except (OSError, ValueError):
            pass  # the stream was closed under the reader (a test's cleanup)

    def _arrived(self, line: str) -> None:
        raise NotImplementedError

    def join(self, timeout: float = 5.0) -> bool:
        """Wait for the stream's end (the process closed it) up to ``timeout`` seconds; whether
        it came."""
        self._reader.join(timeout)
        return not self._reader.is_alive()


class OutputLines(_LineReader):
    """The lines of a child's output stream, read as they come. Take the next one that a test
    wants (waiting for it), or all that came so far; every line taken is kept in :attr:`seen`,
    for assertions and failure messages."""

    def __init__(self, stream: IO[str]) -> None:
        self.seen: list[str] = []
        self._queue: queue.Queue[str] = queue.Queue()
        super().__init__(stream)

    def _arrived(self, line: str) -> None:
        self._queue.put(line)

    def next(self, wanted: Callable[[str], object], timeout: float) -> str | None:
        """The next line for which ``wanted(line)`` is true (the lines before it are passed
        over), or None when none came within ``timeout`` seconds."""
        deadline = time.monotonic() + timeout
        while (remaining := deadline - time.monotonic()) > 0:
            try:
                line = self._queue.get(timeout=min(remaining, 0.2))
            except queue.Empty:
                continue
            self.seen.append(line)
            if wanted(line):
                return line
        return None

    def expect(self, text: str, timeout: float, context: Callable[[], str]) -> str:
        """The next line containing ``text``; after ``timeout`` seconds without one, an
        AssertionError saying so and what ``context()`` tells of the process."""
        line = self.next(lambda line: text in line, timeout)
        if line is None:
            raise AssertionError(f"no line containing {text!r} within {timeout} s; {context()}")
        return line

    def drain(self) -> list[str]:
        """The lines that came and were not taken yet (taken now)."""
        taken = []
        while not self._queue.empty():
            taken.append(self._queue.get())
        self.seen.extend(taken)
        return taken


class KeptLines(_LineReader):
    """Every line of a child's output stream, kept in order as they come; search them, waiting
    for a line to come."""

    def __init__(self, stream: IO[str]) -> None:
        self.lines: list[str] = []
        super().__init__(stream)

    def _arrived(self, line: str) -> None:
        self.lines.append(line)

    def first(
        self,
        text: str,
        timeout: float,
        *,
        after: int = 0,
        ended: Callable[[], bool] = lambda: False,
    ) -> str | None:
        """The first line from index ``after`` on that contains ``text``, waiting for it up to
        ``timeout`` seconds, or until ``ended()`` says the process wrote all it will (its last
        lines are read first); None when none came."""
        deadline = time.monotonic() + timeout
        while True:
            found = next((line for line in self.lines[after:] if text in line), None)
            if found is not None:
                return found
            if ended():
                self.join()
                return next((line for line in self.lines[after:] if text in line), None)
            if time.monotonic() > deadline:
                return None
            time.sleep(0.02)

    @property
    def text(self) -> str:
        """The lines so far, joined."""
        return "\n".join(self.lines)


def ament_package(
    prefix: Path,
    name: str,
    executables: Mapping[str, str] | None = None,
    files: Mapping[str, str] | None = None,
) -> Path:
    """Package ``name`` in the ROS-style install prefix ``prefix`` (what AMENT_PREFIX_PATH
    lists), laid out as colcon lays it out: its marker in the ament index, its share folder with
    ``files`` (relative path: text), and ``executables`` (name: script) in ``lib/NAME``. The
    prefix."""
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True, exist_ok=True)
    (index / name).touch()
    share = prefix / "share" / name
    share.mkdir(parents=True, exist_ok=True)
    for relative, text in (files or {}).items():
        (share / relative).parent.mkdir(parents=True, exist_ok=True)
        (share / relative).write_text(text)
    lib = prefix / "lib" / name
    lib.mkdir(parents=True, exist_ok=True)
    for executable, script in (executables or {}).items():
        (lib / executable).write_text(script)
        (lib / executable).chmod(0o755)
    return prefix


def sleepers(marker: str) -> list[int]:
    """Pids of the live ``sleep MARKER`` processes (a test's own, by its unique ``marker``)."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            command = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if command[:2] == [b"sleep", marker.encode()]:
            found.append(int(entry.name))
    return found


def assert_docs_show(test_file: str, first_line: str, docs_file: str) -> None:
    """``docs_file`` (under docs/) shows ``test_file`` as a Python block, from ``first_line``
    to the line above its ``test_the_docs_show_this_file``."""
    here = Path(test_file).read_text()
    end = here.index("\n\n\ndef test_the_docs_show_this_file")
    example = here[here.index(first_line) : end]
    docs = (Path(__file__).parents[1] / "docs" / docs_file).read_text()
    assert f"```python\n{example}\n```" in docs
