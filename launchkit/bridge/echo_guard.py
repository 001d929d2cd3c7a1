"""Echo suppression: a message the bridge carried one way is never carried back.

launchkit's side knows the publisher of every sample (the GID in rmw_zenoh's attachment), so the
bridge drops samples from its own launchkit publishers by GID. rclpy's message info has no
publisher GID (Jazzy's ``take_message`` returns source timestamp and sequence numbers only), so on
the DDS side the bridge recognises its own writes by what it knows of each: the writer's
sequence number (Fast DDS numbers a writer's samples 1, 2, 3...), the bytes, and the wall-clock
window in which the write happened (the sample's source timestamp falls inside it). Fast DDS
may hand the bytes back padded with zeros to a multiple of 4 (RTPS alignment).
"""

from __future__ import annotations

import hashlib
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from typing import Any

_REMEMBERED = 4096  # writes per topic kept for recognition (a few seconds at high rates)


def _digest(data: bytes) -> bytes:
    return hashlib.blake2b(data, digest_size=16).digest()


class DdsWrites:
    """The bridge's writes to one DDS topic, to recognise them when they come back."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._sequence = 0
        self._writes: OrderedDict[int, tuple[bytes, int, int, int]] = OrderedDict()

    def write(self, data: bytes, publish: Callable[[bytes], Any]) -> None:
        """Call ``publish(data)`` and remember the write."""
        digest = _digest(data)
        with self._lock:
            before = time.time_ns()
            publish(data)
            after = time.time_ns()
            self._sequence += 1
            self._writes[self._sequence] = (digest, len(data), before, after)
            while len(self._writes) > _REMEMBERED:
                self._writes.popitem(last=False)

    def is_own(self, data: bytes, info: dict[str, Any]) -> bool:
        """Whether a sample taken from DDS (``info``: rclpy's message info) is a write of ours."""
        sequence = info.get("publication_sequence_number")
        stamp = info.get("source_timestamp")
        with self._lock:
            write = self._writes.get(sequence) if isinstance(sequence, int) else None
        if write is None or not isinstance(stamp, int):
            return False
        digest, length, before, after = write
        if not before <= stamp <= after or not 0 <= len(data) - length < 4:
            return False
        return not any(data[length:]) and digest == _digest(data[:length])


class EchoGuard:
    """What the routes of all topics share: the bridge's own launchkit GIDs and DDS writes."""

    def __init__(self) -> None:
        self.zenoh_gids: set[bytes] = set()
        self._dds: dict[str, DdsWrites] = {}
        self._lock = threading.Lock()

    def dds_writes(self, topic: str) -> DdsWrites:
        """The record of the bridge's writes to DDS topic ``topic``."""
        with self._lock:
            return self._dds.setdefault(topic, DdsWrites())
