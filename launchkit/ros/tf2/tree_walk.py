"""Walking the frame tree between two frames (tf2's ``walkToTopParent`` and
``getLatestCommonTime``).

A walk climbs from the source frame towards the root, then from the target frame until it meets
the source's path; an accumulator collects what each step contributes (the transform, or just
the parent). Time 0 first becomes the latest time every link on the way shares. The errors and
their messages are tf2's, including which of two failures it reports.
"""

from __future__ import annotations

import enum
from typing import Protocol

from launchkit.ros.tf2.exceptions import TF2Error
from launchkit.ros.tf2.frame_report import as_string
from launchkit.ros.tf2.frames import FrameTable
from launchkit.ros.tf2.time_cache import FrameCache, Lookup, TransformStorage
from launchkit.rotations import Quaternion, Vector, conjugate, quaternion_multiply, rotate

MAX_GRAPH_DEPTH = 1000
_NEVER = 2**63  # later than any time: "no time seen yet"


class WalkEnding(enum.Enum):
    """How the two frames turned out to be related."""

    IDENTITY = 0
    TARGET_PARENT_OF_SOURCE = 1
    SOURCE_PARENT_OF_TARGET = 2
    FULL_PATH = 3


class Accumulator(Protocol):
    """What a walk collects on its way."""

    def gather(self, cache: FrameCache, time: int) -> Lookup:
        """Read one link at ``time``; its data (with the parent) or the failure."""

    def accum(self, source: bool) -> None:
        """Add the link just gathered to the source's (or the target's) side."""

    def finalize(self, ending: WalkEnding, time: int) -> None:
        """The walk ended so, at ``time``."""


class ParentAccumulator:
    """Collects nothing: whether a path exists is all that is asked (``canTransform``)."""

    def gather(self, cache: FrameCache, time: int) -> Lookup:
        """The link's parent at ``time``, not interpolated."""
        return cache.get_parent(time)

    def accum(self, source: bool) -> None:
        """Nothing to add."""

    def finalize(self, ending: WalkEnding, time: int) -> None:
        """Nothing to finish."""


class TransformAccumulator:
    """Composes the links into the transform from the source frame to the target frame."""

    def __init__(self) -> None:
        self.link: TransformStorage | None = None
        self.source_rotation: Quaternion = (0.0, 0.0, 0.0, 1.0)
        self.source_translation: Vector = (0.0, 0.0, 0.0)
        self.target_rotation: Quaternion = (0.0, 0.0, 0.0, 1.0)
        self.target_translation: Vector = (0.0, 0.0, 0.0)
        self.rotation: Quaternion = (0.0, 0.0, 0.0, 1.0)
        self.translation: Vector = (0.0, 0.0, 0.0)
        self.time = 0

    def gather(self, cache: FrameCache, time: int) -> Lookup:
        """The link at ``time``, interpolated; kept for :meth:`accum`."""
        found = cache.get_data(time)
        self.link = found.data
        return found

    def accum(self, source: bool) -> None:
        """Move the source's (or the target's) side up by the link just gathered."""
        assert self.link is not None
        rotation, translation = self.link.rotation, self.link.translation
        if source:
            self.source_translation = _add(rotate(rotation, self.source_translation), translation)
            self.source_rotation = quaternion_multiply(rotation, self.source_rotation)
        else:
            self.target_translation = _add(rotate(rotation, self.target_translation), translation)
            self.target_rotation = quaternion_multiply(rotation, self.target_rotation)

    def finalize(self, ending: WalkEnding, time: int) -> None:
        """Combine both sides into the result."""
        if ending is WalkEnding.TARGET_PARENT_OF_SOURCE:
            self.rotation, self.translation = self.source_rotation, self.source_translation
        elif ending is not WalkEnding.IDENTITY:
            inverse = conjugate(self.target_rotation)
            inverse_translation = rotate(inverse, _negate(self.target_translation))
            if ending is WalkEnding.SOURCE_PARENT_OF_TARGET:
                self.rotation, self.translation = inverse, inverse_translation
            else:
                self.translation = _add(
                    rotate(inverse, self.source_translation), inverse_translation
                )
                self.rotation = quaternion_multiply(inverse, self.source_rotation)
        self.time = time


def walk_to_top_parent(
    frames: FrameTable, accumulator: Accumulator, time: int, target: int, source: int
) -> tuple[TF2Error, str]:
    """Walk from ``source`` and ``target`` to their common parent at ``time`` (0: the latest
    common time); ``(NO_ERROR, "")`` when the accumulator got the whole path, else tf2's error
    code and message."""
    if source == target:
        accumulator.finalize(WalkEnding.IDENTITY, time)
        return TF2Error.NO_ERROR, ""
    if time == 0:
        code, time, message = latest_common_time(frames, target, source)
        if code != TF2Error.NO_ERROR:
            return code, message

    frame = top_parent = source
    stopped: Lookup | None = None  # the source side's failure, reported if nothing else is
    depth = 0
    while frame != 0:
        cache = frames.cache(frame)
        if cache is None:  # the root of the tree
            top_parent = frame
            break
        found = accumulator.gather(cache, time)
        if found.data is None:  # there may still be a path from the target's side
            top_parent = frame
            stopped = found
            break
        if frame == target:
            accumulator.finalize(WalkEnding.TARGET_PARENT_OF_SOURCE, time)
            return TF2Error.NO_ERROR, ""
        accumulator.accum(True)
        top_parent, frame = frame, found.data.parent
        depth += 1
        if depth > MAX_GRAPH_DEPTH:
            return TF2Error.LOOKUP_ERROR, _loop_message(frames)

    frame = target
    depth = 0
    while frame != top_parent:
        cache = frames.cache(frame)
        if cache is None:
            break
        found = accumulator.gather(cache, time)
        if found.data is None:
            return found.code, _between(frames, found.message, source, target)
        if frame == source:
            accumulator.finalize(WalkEnding.SOURCE_PARENT_OF_TARGET, time)
            return TF2Error.NO_ERROR, ""
        accumulator.accum(False)
        frame = found.data.parent
        depth += 1
        if depth > MAX_GRAPH_DEPTH:
            return TF2Error.LOOKUP_ERROR, _loop_message(frames)

    if frame != top_parent:
        if stopped is not None:
            return stopped.code, _between(frames, stopped.message, source, target)
        return TF2Error.CONNECTIVITY_ERROR, connectivity_message(frames, source, target)
    accumulator.finalize(WalkEnding.FULL_PATH, time)
    return TF2Error.NO_ERROR, ""


def latest_common_time(frames: FrameTable, target: int, source: int) -> tuple[TF2Error, int, str]:
    """``(NO_ERROR, time, "")``: the latest time for which every link between the frames has
    data (0 when they are all static); else tf2's error code and message."""
    if source == 0 or target == 0:
        return TF2Error.LOOKUP_ERROR, 0, ""
    if source == target:
        cache = frames.cache(source)
        return TF2Error.NO_ERROR, cache.latest_timestamp() if cache is not None else 0, ""

    # from the source up: each link's newest stamp and parent
    source_links: list[tuple[int, int]] = []
    frame, common, depth = source, _NEVER, 0
    while frame != 0:
        cache = frames.cache(frame)
        if cache is None:
            break
        stamp, parent = cache.latest_time_and_parent()
        if parent == 0:
            break
        if stamp != 0:
            common = min(common, stamp)
        source_links.append((stamp, parent))
        frame = parent
        if frame == target:
            return TF2Error.NO_ERROR, _or_zero(common), ""
        depth += 1
        if depth > MAX_GRAPH_DEPTH:
            return TF2Error.LOOKUP_ERROR, 0, _loop_message(frames)

    # from the target up, until a parent on the source's way
    frame, common, depth = target, _NEVER, 0
    common_parent = 0
    source_parents = [parent for _, parent in source_links]
    while True:
        cache = frames.cache(frame)
        if cache is None:
            break
        stamp, parent = cache.latest_time_and_parent()
        if parent == 0:
            break
        if stamp != 0:
            common = min(common, stamp)
        if parent in source_parents:
            common_parent = parent
            break
        frame = parent
        if frame == source:
            return TF2Error.NO_ERROR, _or_zero(common), ""
        depth += 1
        if depth > MAX_GRAPH_DEPTH:
            return TF2Error.LOOKUP_ERROR, 0, _loop_message(frames)

    if common_parent == 0:
        return TF2Error.CONNECTIVITY_ERROR, 0, connectivity_message(frames, source, target)
    for stamp, parent in source_links:
        if stamp != 0:
            common = min(common, stamp)
        if parent == common_parent:
            break
    return TF2Error.NO_ERROR, _or_zero(common), ""


def connectivity_message(frames: FrameTable, source: int, target: int) -> str:
    """tf2's message for two frames in different trees (its missing space included)."""
    return (
        f"Could not find a connection between '{frames.name(target)}' and "
        f"'{frames.name(source)}' because they are not part of the same tree."
        "Tf has two or more unconnected trees."
    )


def _between(frames: FrameTable, message: str, source: int, target: int) -> str:
    return (
        f"{message}, when looking up transform from frame [{frames.name(source)}] "
        f"to frame [{frames.name(target)}]"
    )


def _loop_message(frames: FrameTable) -> str:
    return f"The tf tree is invalid because it contains a loop.\n{as_string(frames)}\n"


def _or_zero(time: int) -> int:
    return 0 if time == _NEVER else time


def _add(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _negate(v: Vector) -> Vector:
    return (-v[0], -v[1], -v[2])
