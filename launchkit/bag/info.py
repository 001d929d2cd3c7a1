"""``launchkit bag info``: what ``ros2 bag info`` (Jazzy) prints, from ``metadata.yaml``.

The layout is rosbag2_py's ``format_bag_meta_data``: labels padded to 19 columns, sizes in
binary units with one decimal, times in local time with nanoseconds, service event topics
counted apart from topics.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from launchkit.bag.metadata import BagError, read_metadata

_INDENT = 19
_NS = 1_000_000_000


def file_size(size: int) -> str:
    """rosbag2's size: ``512 B``, ``1.5 KiB``, ... (one decimal from KiB on)."""
    value = float(size)
    units = ("B", "KiB", "MiB", "GiB", "TiB")
    index = 0
    while value >= 1024 and index < len(units) - 1:
        value /= 1024
        index += 1
    return f"{value:.0f} {units[index]}" if index == 0 else f"{value:.1f} {units[index]}"


def seconds(nanoseconds: int) -> str:
    """``SECONDS.NNNNNNNNN`` (nine digits of fraction)."""
    whole, fraction = divmod(nanoseconds, _NS)
    return f"{whole}.{fraction:09d}"


def time_point(nanoseconds: int) -> str:
    """``Nov 22 2026 10:00:00.123456789 (1795..123456789)`` in local time, as rosbag2."""
    whole, fraction = divmod(nanoseconds, _NS)
    try:
        local = time.localtime(whole)
    except (OverflowError, OSError, ValueError):  # a bag without messages starts at int64 max
        local = time.localtime(0)
    date = time.strftime("%b %e %Y", local)
    clock = time.strftime("%H:%M:%S", local)
    return f"{date} {clock}.{fraction:09d} ({seconds(nanoseconds)})"


def is_service_event(name: str, type_name: str) -> bool:
    """rosbag2's test for a service introspection topic."""
    return (
        "/srv/" in type_name and type_name.endswith("_Event") and name.endswith("/_service_event")
    )


def directory_size(path: Path) -> int:
    """Bytes of the bag's files (the folder's top level, as rcutils counts it)."""
    return sum(p.stat().st_size for p in path.iterdir() if p.is_file())


def _topics(info: dict[str, Any]) -> list[tuple[str, str, int, str]]:
    topics = []
    for entry in info.get("topics_with_message_count") or []:
        meta = entry.get("topic_metadata") or {}
        topics.append(
            (
                str(meta.get("name", "")),
                str(meta.get("type", "")),
                int(entry.get("message_count", 0)),
                str(meta.get("serialization_format", "")),
            )
        )
    return topics


def format_info(path: Path, info: dict[str, Any]) -> str:
    """The text ``ros2 bag info PATH`` prints for the metadata ``info``."""
    try:
        start = int(info["starting_time"]["nanoseconds_since_epoch"])
        duration = int(info["duration"]["nanoseconds"])
        count = int(info["message_count"])
    except (KeyError, TypeError, ValueError) as exc:
        raise BagError(f"{path / 'metadata.yaml'}: malformed field {exc}") from None
    topics = _topics(info)
    services = [t for t in topics if is_service_event(t[0], t[1])]
    plain = [t for t in topics if not is_service_event(t[0], t[1])]
    pad = " " * _INDENT
    files = [str(f) for f in info.get("relative_file_paths") or []]
    lines = [
        "",
        "Files:             " + f"\n{pad}".join(files),
        f"Bag size:          {file_size(directory_size(path))}",
        f"Storage id:        {info['storage_identifier']}",
        f"ROS Distro:        {info.get('ros_distro') or 'unknown'}",
        f"Duration:          {seconds(duration)}s",
        f"Start:             {time_point(start)}",
        f"End:               {time_point(start + duration)}",
        f"Messages:          {count - sum(t[2] for t in services)}",
        "Topic information: "
        + f"\n{pad}".join(
            f"Topic: {name} | Type: {kind} | Count: {n} | Serialization Format: {fmt}"
            for name, kind, n, fmt in plain
        ),
        f"Service:           {len(services)}",
        "Service information: "
        + f"\n{pad}  ".join(
            f"Service: {name.removesuffix('/_service_event')} | "
            f"Type: {kind.removesuffix('_Event')} | Event Count: {n} | "
            f"Serialization Format: {fmt}"
            for name, kind, n, fmt in services
        ),
    ]
    return "\n".join(lines)


def topic_names(info: dict[str, Any]) -> str:
    """``ros2 bag info -t``: the topic names, one a line (service event topics left out)."""
    return "\n".join(name for name, kind, _, _ in _topics(info) if not is_service_event(name, kind))


def bag_info(path: Path, names_only: bool = False) -> str:
    """What ``launchkit bag info [-t] PATH`` prints."""
    info = read_metadata(path)
    return topic_names(info) if names_only else format_info(path, info)
