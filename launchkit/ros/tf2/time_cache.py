"""One frame's transforms to its parent over time (tf2's ``TimeCache``), and the single
timeless transform of a static frame (``StaticCache``).

A time cache keeps ``cache_time`` of history behind its newest stamp, ordered by stamp, and
answers for any time between its oldest and newest stamps by interpolating its two neighbours.
A time outside them is refused with tf2's extrapolation messages; time 0 means the newest.
"""

from __future__ import annotations

from bisect import bisect_right
from typing import NamedTuple, Protocol

from launchkit.ros.tf2.exceptions import TF2Error
from launchkit.ros.tf2.rotation import lerp, slerp
from launchkit.ros.tf2.time_points import display
from launchkit.rotations import Quaternion, Vector


class TransformStorage(NamedTuple):
    """One transform of a frame to its parent at a stamp (frame numbers, not names)."""

    stamp: int
    rotation: Quaternion
    translation: Vector
    parent: int
    child: int


class Lookup(NamedTuple):
    """What a cache answers for a time: the data (None if it has none there) and, if not, the
    error code and message tf2 gives."""

    data: TransformStorage | None
    code: TF2Error = TF2Error.NO_ERROR
    message: str = ""


class FrameCache(Protocol):
    """What the buffer asks of a frame's cache."""

    def get_data(self, time: int) -> Lookup:
        """The transform at ``time`` (0: the newest), interpolated where needed."""

    def get_parent(self, time: int) -> Lookup:
        """The transform whose parent holds at ``time``, not interpolated."""

    def insert(self, data: TransformStorage) -> bool:
        """Add ``data``; False when it is too old to keep."""

    def clear(self) -> None:
        """Forget the history (a static frame keeps its transform)."""

    def latest_time_and_parent(self) -> tuple[int, int]:
        """The newest stamp and its parent (0, 0 when empty; a static frame's stamp is 0)."""

    def latest_timestamp(self) -> int:
        """The newest stamp (0 when empty or static)."""

    def oldest_timestamp(self) -> int:
        """The oldest stamp (0 when empty or static)."""

    def __len__(self) -> int:
        """How many transforms are kept."""


class TimeCache:
    """A frame's transforms to its parent over the last ``max_storage_ns`` nanoseconds."""

    def __init__(self, max_storage_ns: int) -> None:
        self.max_storage_ns = max_storage_ns
        # oldest first; among equal stamps, in the order they came (tf2 keeps its list newest
        # first, the newest arrival in front: the same order read backwards)
        self._stamps: list[int] = []
        self._items: list[TransformStorage] = []

    def __len__(self) -> int:
        return len(self._items)

    def _closest(
        self, time: int
    ) -> tuple[TransformStorage | None, TransformStorage | None, Lookup]:
        """The stored transform(s) around ``time``: ``(older, newer, Lookup())``, ``newer``
        None when ``older`` is exactly it; or ``(None, None, the error)``."""
        items = self._items
        if not items:
            # tf2 sets the code but no message here (the caller's text stays as it was)
            return None, None, Lookup(None, TF2Error.NO_DATA_FOR_EXTRAPOLATION_ERROR)
        if time == 0:
            return items[-1], None, Lookup(None)
        if len(items) == 1:
            only = items[0]
            if only.stamp == time:
                return only, None, Lookup(None)
            return None, None, _no_data(time, only.stamp)
        latest, earliest = items[-1], items[0]
        if time == latest.stamp:
            return latest, None, Lookup(None)
        if time == earliest.stamp:
            return earliest, None, Lookup(None)
        if time > latest.stamp:
            return None, None, _future(time, latest.stamp)
        if time < earliest.stamp:
            return None, None, _past(time, earliest.stamp)
        older = bisect_right(self._stamps, time) - 1
        return items[older], items[older + 1], Lookup(None)

    def get_data(self, time: int) -> Lookup:
        """The transform at ``time`` (0: the newest), interpolated where needed."""
        older, newer, failure = self._closest(time)
        if older is None:
            return failure
        if newer is None or older.parent != newer.parent:
            return Lookup(older)
        return Lookup(_interpolate(older, newer, time))

    def get_parent(self, time: int) -> Lookup:
        """The transform whose parent holds at ``time``, not interpolated."""
        older, _, failure = self._closest(time)
        return failure if older is None else Lookup(older)

    def insert(self, data: TransformStorage) -> bool:
        """Add ``data`` in stamp order (an exact duplicate is dropped); False, and nothing
        added, when it is older than the newest by more than the storage time."""
        latest = self.latest_timestamp()
        self._prune(latest)
        if self._items and data.stamp < latest - self.max_storage_ns:
            return False
        position = bisect_right(self._stamps, data.stamp)
        same = position - 1
        while same >= 0 and self._stamps[same] == data.stamp:
            if self._items[same] == data:
                return True
            same -= 1
        self._stamps.insert(position, data.stamp)
        self._items.insert(position, data)
        return True

    def _prune(self, latest: int) -> None:
        drop = 0
        while drop < len(self._stamps) and self._stamps[drop] + self.max_storage_ns < latest:
            drop += 1
        if drop:
            del self._stamps[:drop]
            del self._items[:drop]

    def clear(self) -> None:
        """Forget every transform."""
        self._stamps.clear()
        self._items.clear()

    def latest_time_and_parent(self) -> tuple[int, int]:
        """The newest stamp and its parent (0, 0 when empty)."""
        if not self._items:
            return 0, 0
        newest = self._items[-1]
        return newest.stamp, newest.parent

    def latest_timestamp(self) -> int:
        """The newest stamp (0 when empty)."""
        return self._stamps[-1] if self._stamps else 0

    def oldest_timestamp(self) -> int:
        """The oldest stamp (0 when empty)."""
        return self._stamps[0] if self._stamps else 0


class StaticCache:
    """A static frame's one transform, valid at every time."""

    def __init__(self) -> None:
        self._data = TransformStorage(0, (0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0), 0, 0)

    def __len__(self) -> int:
        return 1

    def get_data(self, time: int) -> Lookup:
        """The transform, stamped ``time``."""
        return Lookup(self._data._replace(stamp=time))

    def get_parent(self, time: int) -> Lookup:
        """The transform (its parent holds at every time)."""
        return Lookup(self._data)

    def insert(self, data: TransformStorage) -> bool:
        """Replace the transform."""
        self._data = data
        return True

    def clear(self) -> None:
        """Nothing: a static transform outlives a clear, as in tf2."""

    def latest_time_and_parent(self) -> tuple[int, int]:
        """Stamp 0 (timeless) and the parent."""
        return 0, self._data.parent

    def latest_timestamp(self) -> int:
        """0: a static transform has no time."""
        return 0

    def oldest_timestamp(self) -> int:
        """0: a static transform has no time."""
        return 0


def _interpolate(older: TransformStorage, newer: TransformStorage, time: int) -> TransformStorage:
    ratio = (time - older.stamp) / (newer.stamp - older.stamp)
    return TransformStorage(
        older.stamp,
        slerp(older.rotation, newer.rotation, ratio),
        lerp(older.translation, newer.translation, ratio),
        older.parent,
        older.child,
    )


def _no_data(time: int, only: int) -> Lookup:
    return Lookup(
        None,
        TF2Error.NO_DATA_FOR_EXTRAPOLATION_ERROR,
        f"Lookup would require extrapolation at time {display(time)}, "
        f"but only time {display(only)} is in the buffer",
    )


def _future(time: int, latest: int) -> Lookup:
    return Lookup(
        None,
        TF2Error.FORWARD_EXTRAPOLATION_ERROR,
        "Lookup would require extrapolation into the future.  Requested time "
        f"{display(time)} but the latest data is at time {display(latest)}",
    )


def _past(time: int, earliest: int) -> Lookup:
    return Lookup(
        None,
        TF2Error.BACKWARD_EXTRAPOLATION_ERROR,
        "Lookup would require extrapolation into the past.  Requested time "
        f"{display(time)} but the earliest data is at time {display(earliest)}",
    )
