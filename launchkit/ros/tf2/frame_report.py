"""A buffer's frames described as tf2 describes them: ``all_frames_as_string`` (one line per
frame with its parent) and ``all_frames_as_yaml`` (parent, sender, rate and time span, what the
``tf2_frames`` service and ``view_frames`` show)."""

from __future__ import annotations

from launchkit.ros.tf2.frames import FrameTable
from launchkit.ros.tf2.time_points import display, to_seconds

_MIN_SPAN_NS = 100_000  # tf2 divides by at least 100 µs when it works out a rate


def as_string(frames: FrameTable) -> str:
    """``Frame CHILD exists with parent PARENT.`` for every frame that has a parent."""
    lines = []
    for number in range(1, len(frames.names)):
        cache = frames.cache(number)
        if cache is None:
            continue
        newest = cache.get_data(0).data
        parent = newest.parent if newest is not None else 0
        lines.append(f"Frame {frames.names[number]} exists with parent {frames.names[parent]}.\n")
    return "".join(lines)


def as_yaml(frames: FrameTable, current_time: int = 0) -> str:
    """Each frame with a transform as a YAML mapping (``[]`` when the buffer knows no frame);
    ``current_time`` (not 0) adds each frame's delay behind it."""
    text = "[]" if len(frames.names) == 1 else ""
    for number in range(1, len(frames.names)):
        cache = frames.cache(number)
        if cache is None:
            continue
        newest = cache.get_data(0).data
        if newest is None:
            continue
        latest, oldest = cache.latest_timestamp(), cache.oldest_timestamp()
        rate = len(cache) * 1e9 / max(latest - oldest, _MIN_SPAN_NS)
        authority = frames.authority.get(number, "no recorded authority")
        text += (
            f"{frames.names[number]}: \n"
            f"  parent: '{frames.names[newest.parent]}'\n"
            f"  broadcaster: '{authority}'\n"
            f"  rate: {rate:.3f}\n"
            f"  most_recent_transform: {display(latest)}\n"
            f"  oldest_transform: {display(oldest)}\n"
        )
        if current_time != 0:
            text += f"  transform_delay: {to_seconds(current_time - latest):.3f}\n"
        text += f"  buffer_length: {to_seconds(latest - oldest):.3f}\n"
    return text
