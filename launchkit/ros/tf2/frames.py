"""The frames a buffer knows: their numbers, names, caches and who last sent each
(tf2's ``frameIDs_``, ``frames_`` and ``frame_authority_``), and frame name validation.

Frame 0 is ``NO_PARENT``, the parent nothing has. A frame gets a number when it is first named,
as a child or as a parent; only a child has a cache.
"""

from __future__ import annotations

from launchkit.ros.tf2.exceptions import InvalidArgumentException, LookupException
from launchkit.ros.tf2.time_cache import FrameCache, StaticCache, TimeCache

NO_PARENT = "NO_PARENT"


class FrameTable:
    """Frame numbers and names, each child frame's cache and its last sender."""

    def __init__(self, cache_time_ns: int) -> None:
        self.cache_time_ns = cache_time_ns
        self.ids: dict[str, int] = {NO_PARENT: 0}
        self.names: list[str] = [NO_PARENT]
        self.caches: list[FrameCache | None] = [None]
        self.authority: dict[int, str] = {}

    def number(self, name: str) -> int:
        """The frame's number (0 when unknown)."""
        return self.ids.get(name, 0)

    def number_or_new(self, name: str) -> int:
        """The frame's number, given one now if it has none."""
        number = self.ids.get(name)
        if number is None:
            number = len(self.names)
            self.ids[name] = number
            self.names.append(name)
            self.caches.append(None)
        return number

    def name(self, number: int) -> str:
        """The frame's name."""
        if number >= len(self.names):
            raise LookupException(f"Reverse lookup of frame id {number} failed!")
        return self.names[number]

    def cache(self, number: int) -> FrameCache | None:
        """The frame's cache (None for a frame that is nobody's child, or frame 0)."""
        return self.caches[number] if number < len(self.caches) else None

    def cache_for(self, number: int, static: bool) -> FrameCache:
        """The frame's cache of the right kind: a new one when the frame had none or had the
        other kind (its history is dropped then, as tf2 does)."""
        cache = self.caches[number]
        if cache is None or isinstance(cache, StaticCache) != static:
            cache = StaticCache() if static else TimeCache(self.cache_time_ns)
            self.caches[number] = cache
        return cache

    def validate(self, caller: str, frame: str) -> int:
        """The number of an existing frame; raises tf2's error for an empty, ``/``-prefixed or
        unknown one (``caller`` names the argument in the message)."""
        if not frame:
            raise InvalidArgumentException(
                f'Invalid argument "{frame}" passed to {caller} - in tf2 frame_ids cannot be empty'
            )
        if frame.startswith("/"):
            raise InvalidArgumentException(
                f'Invalid argument "{frame}" passed to {caller} - '
                "in tf2 frame_ids cannot start with a '/'"
            )
        number = self.number(frame)
        if number == 0:
            raise LookupException(f'"{frame}" passed to {caller} does not exist. ')
        return number

    def check(self, caller: str, frame: str) -> tuple[int, str]:
        """As :meth:`validate` without raising: ``(number, "")`` or ``(0, message)``."""
        if not frame:
            rationale = "in tf2 frame_ids cannot be empty"
        elif frame.startswith("/"):
            rationale = "in tf2 frame_ids cannot start with a '/'"
        else:
            number = self.number(frame)
            if number:
                return number, ""
            rationale = "frame does not exist"
        return 0, f'Invalid frame ID "{frame}" passed to {caller} - {rationale}'

    def clear(self) -> None:
        """Forget every frame's history (static transforms stay)."""
        for cache in self.caches:
            if cache is not None:
                cache.clear()
