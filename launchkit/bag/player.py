"""``launchkit bag play``'s core: read a bag ahead, publish each message at its recorded time.

A reader thread fills a bounded queue from rosbags' reader (rosbag2's
``--read-ahead-queue-size``); the playing thread waits on a :class:`PlaybackClock` for each
message's time and publishes its bytes as they were recorded. Topics keep the QoS their
publishers offered when recording (from the bag's metadata), and are remapped by the player
node's ``--ros-args -r`` rules, as ``ros2 bag play --remap`` does.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosbags.interfaces import Connection, ConnectionExtRosbag2, MessageDefinitionFormat
from rosbags.rosbag2 import Reader, ReaderError
from rosbags.typesys import get_types_from_msg

from launchkit.bag.metadata import BagError
from launchkit.bag.playclock import PlaybackClock, Wait
from launchkit.bag.qos import offer_for_recorded
from launchkit.bag.selection import TopicSelection
from launchkit.ros.msgs import MessageTypeError, get_message, register_types
from launchkit.ros.node import Node
from launchkit.ros.qos import QoSProfile, ReliabilityPolicy
from launchkit.ros.topics import Publisher

_NS = 1_000_000_000
_END_OF_PASS = None  # the reader has given every message of one pass
#: Bytes the reader may hold ahead besides the message count (1000 camera frames are 2 GB).
READ_AHEAD_BYTES = 256 * 1024 * 1024


@dataclass(frozen=True)
class PlayOptions:
    """How to play (``ros2 bag play``'s options of the same names)."""

    selection: TopicSelection = field(default_factory=lambda: TopicSelection(all=True))
    rate: float = 1.0
    loop: bool = False
    start_offset: float = 0.0  # seconds into the bag
    clock_hz: float = 0.0  # publish /clock at this rate; 0: do not
    delay: float = 0.0  # seconds to wait before playing (each loop)
    start_paused: bool = False
    read_ahead: int = 1000


_BUDGET_UNIT = 64 * 1024


def _units(data: bytes) -> int:
    """The read-ahead budget a message takes: at least one unit (tiny ones count too), at most
    the whole budget (a message larger than it still gets through, alone)."""
    return min(max(1, len(data) // _BUDGET_UNIT), READ_AHEAD_BYTES // _BUDGET_UNIT)


def open_bag(path: Path) -> Reader:
    """An open rosbags reader of ``path``, or a :class:`BagError` saying what is wrong."""
    if not path.exists():
        raise BagError(f"{path}: no such bag", expected="a rosbag2 bag directory")
    try:
        reader = Reader(path)
        reader.open()
    except FileNotFoundError as exc:
        raise BagError(
            f"{path}: {exc}",
            expected="a rosbag2 bag directory",
            hint=f"a recorder that was killed leaves no metadata: `launchkit bag reindex {path}`",
        ) from None
    except ReaderError as exc:
        raise BagError(f"{path}: cannot read the bag: {exc}") from None
    return reader


def _message_type(connection: Connection) -> Any:
    """The class of a connection's type; types launchkit lacks are taken from the bag."""
    try:
        return get_message(connection.msgtype)
    except MessageTypeError:
        if connection.msgdef.format != MessageDefinitionFormat.MSG:
            raise
        register_types(get_types_from_msg(connection.msgdef.data, connection.msgtype))
        return get_message(connection.msgtype)


class Player:
    """Publishes a bag's messages at their recorded times (see the module docstring)."""

    def __init__(self, node: Node, reader: Reader, options: PlayOptions) -> None:
        self.node = node
        self.reader = reader
        self.options = options
        self.published = 0
        self._log = node.get_logger()
        self._queue: queue.Queue[tuple[Publisher, int, bytes] | None] = queue.Queue(
            max(1, options.read_ahead)
        )
        self._stop = threading.Event()
        self._ahead = threading.Semaphore(READ_AHEAD_BYTES // _BUDGET_UNIT)
        self.start_time = reader.start_time + int(options.start_offset * _NS)
        self.clock = PlaybackClock(self.start_time, options.rate, options.start_paused)
        self.connections, self._publishers = self._make_publishers()
        self._clock_pub: Publisher | None = None
        if options.clock_hz > 0:
            clock_type = get_message("rosgraph_msgs/msg/Clock")
            self._clock_pub = node.create_publisher(
                clock_type, "/clock", QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
            )

    def _make_publishers(self) -> tuple[list[Connection], dict[int, Publisher]]:
        selection = self.options.selection
        by_topic: dict[str, Publisher] = {}
        publishers: dict[int, Publisher] = {}
        chosen: list[Connection] = []
        for connection in self.reader.connections:
            topic = connection.topic
            if not selection.wants(topic) or (self.options.clock_hz > 0 and topic == "/clock"):
                continue
            if topic not in by_topic:
                try:
                    msg_type = _message_type(connection)
                except Exception as exc:  # unknown type, malformed definition in the bag
                    self._log.warn(
                        f"Ignoring topic '{topic}' of type '{connection.msgtype}': {exc}"
                    )
                    continue
                ext = connection.ext
                recorded = ext.offered_qos_profiles if isinstance(ext, ConnectionExtRosbag2) else []
                qos = offer_for_recorded(topic, recorded, self._log.warn)
                by_topic[topic] = self.node.create_publisher(msg_type, topic, qos)
            chosen.append(connection)
            publishers[connection.id] = by_topic[topic]
        return chosen, publishers

    # threads ----------------------------------------------------------------------------
    def _messages(self) -> Iterator[tuple[Publisher, int, bytes]]:
        for connection, timestamp, data in self.reader.messages(
            self.connections, start=self.start_time
        ):
            yield self._publishers[connection.id], timestamp, data

    def _read(self) -> None:
        try:
            while not self._stop.is_set():
                for item in self._messages():
                    if not self._put(item):
                        return
                if not self._put(_END_OF_PASS) or not self.options.loop:
                    return
        except Exception as exc:  # a damaged storage file: say so and end the playback
            self._log.error(f"Reading the bag failed: {exc}")
            self._put(_END_OF_PASS)

    def _put(self, item: tuple[Publisher, int, bytes] | None) -> bool:
        units = 0 if item is None else _units(item[2])
        taken = 0
        while taken < units:  # the byte budget: wait until the player has used enough
            if self._ahead.acquire(timeout=0.2):
                taken += 1
            elif self._stop.is_set():
                return False
        while not self._stop.is_set():
            try:
                self._queue.put(item, timeout=0.2)
                return True
            except queue.Full:
                continue
        return False

    def _send_clock(self) -> None:
        assert self._clock_pub is not None
        sec, nanosec = divmod(self.clock.now(), _NS)
        clock_type = get_message("rosgraph_msgs/msg/Clock")
        time_type = get_message("builtin_interfaces/msg/Time")
        self._clock_pub.publish(clock_type(clock=time_type(sec=sec, nanosec=nanosec)))

    def _publish_clock(self) -> None:
        period = 1.0 / self.options.clock_hz
        while not self._stop.wait(period):
            self._send_clock()

    # playing ----------------------------------------------------------------------------
    def play(self) -> int:
        """Play until the end (forever with ``loop``) or :meth:`stop`; messages published."""
        if not self.connections:
            self._log.warn("No topic of the bag is selected: nothing to play")
            return 0
        threads = [threading.Thread(target=self._read, daemon=True, name="bag reader")]
        if self._clock_pub is not None:
            self.clock.jump(self.start_time)
            self._send_clock()  # nodes on sim time know the bag's time before its first message
            threads.append(threading.Thread(target=self._publish_clock, daemon=True, name="clock"))
        for thread in threads:
            thread.start()
        try:
            self._play_passes()
        finally:
            self.stop()
            for thread in threads:
                thread.join(5.0)
        return self.published

    def _play_passes(self) -> None:
        if self.options.delay > 0 and self._stop.wait(self.options.delay):
            return
        self.clock.jump(self.start_time)
        while not self._stop.is_set():
            item = self._queue.get()
            if item is _END_OF_PASS:
                if not self.options.loop or self._stop.is_set():
                    return
                if self.options.delay > 0 and self._stop.wait(self.options.delay):
                    return
                self.clock.jump(self.start_time)
                continue
            publisher, timestamp, data = item
            self._ahead.release(_units(data))
            waited = self.clock.wait_until(timestamp)
            if waited is Wait.STOPPED:
                return
            if waited is Wait.STEP:
                self.clock.jump(timestamp)
            publisher.publish(data)
            self.published += 1

    def stop(self) -> None:
        """End the playback (from any thread)."""
        self._stop.set()
        self.clock.stop()
        try:  # wake a player blocked on an empty queue
            self._queue.put_nowait(_END_OF_PASS)
        except queue.Full:
            pass
