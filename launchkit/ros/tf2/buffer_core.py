"""``BufferCore``: tf2's transform buffer without ROS (what ``tf2_py.BufferCore`` offers).

It holds, per frame, the transforms to its parent over the last ``cache_time`` (10 s by
default) or one static transform, and answers lookups between any two frames of a tree at a
time (0: the latest time they share), interpolating between stamps and refusing to extrapolate,
with tf2's exceptions and messages. It is thread-safe: a listener fills it from the spinning
thread while other threads look up.

Times are what tf2 accepts (:mod:`launchkit.ros.tf2.time_points`); results are
``geometry_msgs/TransformStamped`` messages.
"""

from __future__ import annotations

import math
import threading
from typing import Any

from launchkit.ros.logging import RcutilsLogger
from launchkit.ros.msgs import get_message
from launchkit.ros.tf2 import frame_report
from launchkit.ros.tf2.exceptions import TF2Error, TransformException, exception_for
from launchkit.ros.tf2.frames import FrameTable
from launchkit.ros.tf2.rotation import as_stored
from launchkit.ros.tf2.time_cache import TransformStorage
from launchkit.ros.tf2.time_points import (
    NS_PER_SECOND,
    display,
    duration_ns,
    sec_nanosec,
    time_ns,
)
from launchkit.ros.tf2.tree_walk import (
    ParentAccumulator,
    TransformAccumulator,
    latest_common_time,
    walk_to_top_parent,
)
from launchkit.rotations import Quaternion, Vector, quaternion_multiply, rotate

DEFAULT_CACHE_TIME_NS = 10 * NS_PER_SECOND

# tf2 reports rejected input through rcutils' unnamed logger
_log = RcutilsLogger("")  # rclpy's get_logger refuses the empty name

Pose = tuple[Quaternion, Vector, int]  # rotation, translation, the time it holds for


class BufferCore:
    """A transform tree over time; ``cache_time`` (a Duration) is how much history each frame
    keeps."""

    def __init__(self, cache_time: Any = None) -> None:
        cache_ns = DEFAULT_CACHE_TIME_NS if cache_time is None else duration_ns(cache_time)
        self._frames = FrameTable(cache_ns)
        self._lock = threading.Lock()

    # adding transforms ---------------------------------------------------------------------
    def set_transform(self, transform: Any, authority: str) -> None:
        """Add ``transform`` (a TransformStamped) to its child frame's history; ``authority``
        names the sender. Invalid or too old input is logged and dropped, as tf2 does."""
        self._set(transform, authority, static=False)

    def set_transform_static(self, transform: Any, authority: str) -> None:
        """Make ``transform`` its child frame's one, timeless transform."""
        self._set(transform, authority, static=True)

    def _set(self, transform: Any, authority: str, static: bool) -> None:
        stamp = time_ns(transform.header.stamp)
        parent = _strip_slash(str(transform.header.frame_id))
        child = _strip_slash(str(transform.child_frame_id))
        t, r = transform.transform.translation, transform.transform.rotation
        translation = (float(t.x), float(t.y), float(t.z))
        rotation = as_stored((float(r.x), float(r.y), float(r.z), float(r.w)))
        if not _acceptable(parent, child, translation, rotation, authority):
            return
        with self._lock:
            frames = self._frames
            number = frames.number_or_new(child)
            cache = frames.cache_for(number, static)
            data = TransformStorage(
                stamp, rotation, translation, frames.number_or_new(parent), number
            )
            if cache.insert(data):
                frames.authority[number] = authority
                return
        _log.warn(
            f"TF_OLD_DATA ignoring data from the past for frame {child} at time "
            f"{display(stamp)} according to authority {authority}\n"
            "Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained"
        )

    def clear(self) -> None:
        """Forget every frame's history (static transforms stay, as in tf2)."""
        with self._lock:
            self._frames.clear()

    # asking ----------------------------------------------------------------------------------
    def can_transform_core(
        self, target_frame: str, source_frame: str, time: Any
    ) -> tuple[int, str]:
        """``(1, "")`` when a lookup would succeed now, else ``(0, why)`` (tf2_py returns ints)."""
        if target_frame == source_frame:
            return 1, ""
        at = time_ns(time)
        with self._lock:
            numbers, message = self._check(target_frame=target_frame, source_frame=source_frame)
            if not numbers:
                return 0, message
            target, source = numbers
            return self._can(target, source, at)

    def can_transform_full_core(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> tuple[int, str]:
        """As :meth:`can_transform_core` for :meth:`lookup_transform_full_core`'s question."""
        target_at, source_at = time_ns(target_time), time_ns(source_time)
        with self._lock:
            numbers, message = self._check(
                target_frame=target_frame, source_frame=source_frame, fixed_frame=fixed_frame
            )
            if not numbers:
                return 0, message
            target, source, fixed = numbers
            result = self._can(target, fixed, target_at)
            return result if not result[0] else self._can(fixed, source, source_at)

    def _check(self, **frames: str) -> tuple[list[int], str]:
        """The numbers of the frames given by argument name, or ``([], why)`` for the first
        that is no usable frame (tf2's ``canTransform`` messages)."""
        numbers = []
        for argument, frame in frames.items():
            number, message = self._frames.check(f"canTransform argument {argument}", frame)
            if not number:
                return [], message
            numbers.append(number)
        return numbers, ""

    def _can(self, target: int, source: int, time: int) -> tuple[int, str]:
        if target == source:
            return 1, ""
        code, message = walk_to_top_parent(self._frames, ParentAccumulator(), time, target, source)
        return (1, "") if code == TF2Error.NO_ERROR else (0, message)

    def lookup_transform_core(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """The transform taking data in ``source_frame`` into ``target_frame`` at ``time`` (0:
        the latest common time), as a TransformStamped; raises tf2's exceptions."""
        at = time_ns(time)
        with self._lock:
            rotation, translation, stamp = self._lookup(target_frame, source_frame, at)
        return _stamped(target_frame, source_frame, rotation, translation, stamp)

    def lookup_transform_full_core(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> Any:
        """The transform of data in ``source_frame`` at ``source_time`` into ``target_frame``
        at ``target_time``, through ``fixed_frame`` (the frame that stays put meanwhile)."""
        target_at, source_at = time_ns(target_time), time_ns(source_time)
        with self._lock:
            for argument, frame in (
                ("target_frame", target_frame),
                ("source_frame", source_frame),
                ("fixed_frame", fixed_frame),
            ):
                self._frames.validate(f"lookupTransform argument {argument}", frame)
            first_rotation, first_translation, _ = self._lookup(
                fixed_frame, source_frame, source_at
            )
            rotation, translation, stamp = self._lookup(target_frame, fixed_frame, target_at)
        combined = quaternion_multiply(rotation, first_rotation)
        moved = rotate(rotation, first_translation)
        return _stamped(
            target_frame,
            source_frame,
            combined,
            (moved[0] + translation[0], moved[1] + translation[1], moved[2] + translation[2]),
            stamp,
        )

    def _lookup(self, target_frame: str, source_frame: str, time: int) -> Pose:
        frames = self._frames
        if target_frame == source_frame:
            if time == 0:
                cache = frames.cache(frames.number(target_frame))
                time = cache.latest_timestamp() if cache is not None else 0
            return (0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0), time
        target = frames.validate("lookupTransform argument target_frame", target_frame)
        source = frames.validate("lookupTransform argument source_frame", source_frame)
        accumulator = TransformAccumulator()
        code, message = walk_to_top_parent(frames, accumulator, time, target, source)
        if code != TF2Error.NO_ERROR:
            raise exception_for(code, message)
        return accumulator.rotation, accumulator.translation, accumulator.time

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        """The latest time both frames have data for, as an rclpy-style Time."""
        from launchkit.ros.clock import Time

        with self._lock:
            target = self._frames.validate("get_latest_common_time", target_frame)
            source = self._frames.validate("get_latest_common_time", source_frame)
            code, time, message = latest_common_time(self._frames, target, source)
        if code != TF2Error.NO_ERROR:
            raise TransformException(message)
        sec, nanosec = sec_nanosec(time)
        return Time(seconds=sec, nanoseconds=nanosec)

    # describing ------------------------------------------------------------------------------
    def all_frames_as_string(self) -> str:
        """``Frame CHILD exists with parent PARENT.``, one line per frame."""
        with self._lock:
            return frame_report.as_string(self._frames)

    def all_frames_as_yaml(self) -> str:
        """Every frame's parent, sender, rate and time span, as YAML."""
        with self._lock:
            return frame_report.as_yaml(self._frames)

    def _frameExists(self, frame_id: str) -> bool:
        """Whether ``frame_id`` has been named (as a child or a parent)."""
        with self._lock:
            return frame_id in self._frames.ids

    def _getFrameStrings(self) -> list[str]:
        """Every frame name the buffer has seen."""
        with self._lock:
            return list(self._frames.names[1:])


def _strip_slash(frame: str) -> str:
    return frame[1:] if frame.startswith("/") else frame


def _acceptable(
    parent: str, child: str, translation: Vector, rotation: Quaternion, authority: str
) -> bool:
    """Whether tf2 takes the transform; logs each reason it does not."""
    fine = True
    if child == parent:
        _log.error(
            f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with frame_id '
            f'and  child_frame_id "{child}" because they are the same'
        )
        fine = False
    if not child:
        _log.error(
            f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" because '
            "child_frame_id not set "
        )
        fine = False
    if not parent:
        _log.error(
            f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from authority '
            f'"{authority}" because frame_id not set'
        )
        fine = False
    if any(math.isnan(v) for v in (*translation, *rotation)):
        values = " ".join(f"{v:f}" for v in translation)
        angles = " ".join(f"{v:f}" for v in rotation)
        _log.error(
            f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority '
            f'"{authority}" because of a nan value in the transform ({values}) ({angles})'
        )
        fine = False
    # tf2 also checks the quaternion's norm, but only after its rotation matrix normalised it,
    # so that check never fires: any non-zero quaternion is accepted, normalised
    return fine


def _stamped(target: str, source: str, rotation: Quaternion, translation: Vector, time: int) -> Any:
    """A TransformStamped result, its rotation read back through tf2's matrix."""
    transform_stamped = get_message("geometry_msgs/msg/TransformStamped")
    header = get_message("std_msgs/msg/Header")
    stamp = get_message("builtin_interfaces/msg/Time")
    transform = get_message("geometry_msgs/msg/Transform")
    vector3 = get_message("geometry_msgs/msg/Vector3")
    quaternion = get_message("geometry_msgs/msg/Quaternion")
    sec, nanosec = sec_nanosec(time)
    x, y, z, w = as_stored(rotation)
    return transform_stamped(
        header=header(stamp=stamp(sec=sec, nanosec=nanosec), frame_id=target),
        child_frame_id=source,
        transform=transform(
            translation=vector3(x=translation[0], y=translation[1], z=translation[2]),
            rotation=quaternion(x=x, y=y, z=z, w=w),
        ),
    )
