"""The recorder's writer thread: a bounded queue in front of the disk.

Subscription callbacks only enqueue; one thread takes messages off the queue and writes them, so
a slow disk never stalls the transport. The queue is bounded in bytes (rosbag2's
``--max-cache-size``): a message that does not fit is dropped and counted, never waited for.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from launchkit.bag.metadata import BagSummary, TopicRecord
from launchkit.bag.storage import BagTopic, BagWriter

OnError = Callable[[BaseException], None]


@dataclass
class _Declare:
    """A topic to declare; the writer thread puts the result in ``done``."""

    record: TopicRecord
    msgdef: str
    done: list[BagTopic] = field(default_factory=list)


_Message = tuple[BagTopic, int, bytes]
_STOP = None


class WriterThread:
    """Owns a :class:`BagWriter`; ``put`` from any thread, ``close`` once at the end."""

    def __init__(self, writer: BagWriter, max_bytes: int, on_error: OnError) -> None:
        self.writer = writer
        self.max_bytes = max_bytes
        self.dropped: dict[str, int] = {}
        self.error: BaseException | None = None
        self.summary: BagSummary | None = None
        self._on_error = on_error
        self._items: deque[_Message | _Declare | None] = deque()
        self._bytes = 0
        self._cond = threading.Condition()
        self._thread = threading.Thread(target=self._run, name="bag writer", daemon=True)
        self._thread.start()

    def declare(self, record: TopicRecord, msgdef: str) -> BagTopic:
        """Declare a topic in the bag (waits for the writer thread; never dropped)."""
        item = _Declare(record, msgdef)
        with self._cond:
            self._items.append(item)
            self._cond.notify_all()
            while not item.done and self.error is None:
                self._cond.wait(1.0)
        if self.error is not None:
            raise RuntimeError(f"the bag writer failed: {self.error}")
        return item.done[0]

    def put(self, topic: BagTopic, timestamp: int, data: bytes) -> bool:
        """Queue a message; False (and counted) if the queue is full or the writer failed."""
        size = len(data)
        with self._cond:
            if self.error is not None or (self._items and self._bytes + size > self.max_bytes):
                name = topic.record.name
                self.dropped[name] = self.dropped.get(name, 0) + 1
                return False
            self._items.append((topic, timestamp, data))
            self._bytes += size
            self._cond.notify_all()
        return True

    def _next(self, idle: float) -> _Message | _Declare | bool | None:
        """The next item, or False after ``idle`` seconds without one."""
        with self._cond:
            if not self._items:
                self._cond.wait(idle)
            if not self._items:
                return False
            item = self._items.popleft()
            if isinstance(item, tuple):
                self._bytes -= len(item[2])
            return item

    def _run(self) -> None:
        writer = self.writer
        try:
            while True:
                item = self._next(writer.options.flush_interval)
                if item is False:
                    writer.flush_if_due()  # quiet topics still reach the disk in time
                elif item is _STOP:
                    self.summary = writer.close()
                    return
                elif isinstance(item, _Declare):
                    topic = writer.add_topic(item.record, item.msgdef)
                    with self._cond:
                        item.done.append(topic)
                        self._cond.notify_all()
                elif isinstance(item, tuple):
                    writer.write(*item)
        except BaseException as exc:  # disk full, permissions...: stop writing, say why
            with self._cond:
                self.error = exc
                self._items.clear()
                self._bytes = 0
                self._cond.notify_all()
            self._on_error(exc)

    def close(self, timeout: float | None = None) -> BagSummary | None:
        """Write what is queued and finish the bag; its summary (None if that failed)."""
        with self._cond:
            self._items.append(_STOP)
            self._cond.notify_all()
        self._thread.join(timeout)
        return self.summary
