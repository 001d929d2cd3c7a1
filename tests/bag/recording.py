"""Recording inside the test process, so a test can wait until the recorder has what it needs."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from launchkit.bag.metadata import BagSummary
from launchkit.bag.recorder import Recorder, RecorderOptions
from launchkit.bag.selection import TopicSelection
from launchkit.bag.storage import BagWriter, WriterOptions
from launchkit.bag.writer_thread import WriterThread
from tests.bag.helpers import Probe
from tests.support import wait_until


@dataclass
class InProcessRecording:
    """A recorder node spun by a thread of the test; ``summary`` is set once closed."""

    recorder: Recorder
    writer: WriterThread
    summary: BagSummary | None = None

    def discover_until(self, topics: int, timeout: float = 30) -> None:
        """Discover until ``topics`` topics are subscribed."""

        def subscribed() -> bool:
            self.recorder.discover()
            return len(self.recorder.subscriptions) >= topics

        wait_until(subscribed, timeout, f"the recorder to subscribe to {topics} topics")

    def wait_received(self, count: int, timeout: float = 30) -> None:
        """Wait until ``count`` messages reached the recorder."""
        wait_until(
            lambda: sum(self.recorder.received.values()) >= count,
            timeout,
            f"{count} messages at the recorder (got {dict(self.recorder.received)})",
        )


@contextmanager
def recording(
    router: str,
    path: Path,
    selection: TopicSelection,
    options: WriterOptions | None = None,
) -> Iterator[InProcessRecording]:
    """Record ``selection`` to ``path`` while the block runs; the bag is closed after it."""
    errors: list[BaseException] = []
    node = Probe(router, "rosbag2_recorder")
    try:
        writer = WriterThread(BagWriter(path, options or WriterOptions()), 1 << 30, errors.append)
        result = InProcessRecording(Recorder(node.node, writer, RecorderOptions(selection)), writer)
        yield result
        result.recorder.stop()
    finally:
        node.close()
    result.summary = writer.close()
    assert not errors, errors
