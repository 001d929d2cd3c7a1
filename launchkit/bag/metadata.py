"""A bag's ``metadata.yaml``, written as rosbag2 (Jazzy, version 9) writes it, and read back.

rosbags' ``Writer`` writes this file only for a bag of one storage file; launchkit splits bags,
so it writes the file itself, with rosbags' QoS serialization and rosbag2's key order.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from rosbags.interfaces import Qos
from rosbags.rosbag2.metadata import dump_qos_v9

from launchkit.errors import UserError

METADATA_FILE = "metadata.yaml"
VERSION = 9
ROS_DISTRO = "jazzy"  # the type hashes launchkit writes are Jazzy's
#: rosbag2's starting time of a bag without messages (``time_point::max()``).
NO_MESSAGES = 2**63 - 1


class BagError(UserError):
    """A bag directory that cannot be read (missing, malformed or damaged)."""


@dataclass
class TopicRecord:
    """One topic of a bag: what rosbag2 lists under ``topics_with_message_count``."""

    name: str
    type: str
    type_hash: str
    qos: Sequence[Qos] = ()
    serialization_format: str = "cdr"
    count: int = 0


@dataclass
class FileRecord:
    """One storage file of a bag and the span of its messages (nanoseconds)."""

    path: str
    start: int = NO_MESSAGES
    end: int = 0
    count: int = 0

    def add(self, timestamp: int) -> None:
        """Count one message written at ``timestamp``."""
        self.count += 1
        self.start = min(self.start, timestamp)
        self.end = max(self.end, timestamp)

    @property
    def duration(self) -> int:
        """Nanoseconds from the first message to the last (0 without messages)."""
        return self.end - self.start if self.count else 0


@dataclass
class BagSummary:
    """Everything ``metadata.yaml`` says about a bag."""

    storage: str
    files: list[FileRecord] = field(default_factory=list)
    topics: list[TopicRecord] = field(default_factory=list)
    compression_mode: str = ""
    compression_format: str = ""
    custom_data: dict[str, str] = field(default_factory=dict)

    @property
    def start(self) -> int:
        """The first message's time (``NO_MESSAGES`` when there is none)."""
        return min((f.start for f in self.files if f.count), default=NO_MESSAGES)

    @property
    def duration(self) -> int:
        """Nanoseconds from the first message of the bag to its last."""
        ends = [f.end for f in self.files if f.count]
        return max(ends) - self.start if ends else 0

    @property
    def message_count(self) -> int:
        """Messages in every file."""
        return sum(f.count for f in self.files)

    def to_dict(self) -> dict[str, Any]:
        """The ``metadata.yaml`` document, keys in rosbag2's order."""

        info: dict[str, Any] = {"version": VERSION, "storage_identifier": self.storage}
        info["duration"] = {"nanoseconds": self.duration}
        info["starting_time"] = {"nanoseconds_since_epoch": self.start}
        info["message_count"] = self.message_count
        info["topics_with_message_count"] = [
            {
                "topic_metadata": {
                    "name": t.name,
                    "type": t.type,
                    "serialization_format": t.serialization_format,
                    "offered_qos_profiles": dump_qos_v9(list(t.qos)),
                    "type_description_hash": t.type_hash,
                },
                "message_count": t.count,
            }
            for t in self.topics
        ]
        info["compression_format"] = self.compression_format
        info["compression_mode"] = self.compression_mode
        info["relative_file_paths"] = [f.path for f in self.files]
        info["files"] = [
            {
                "path": f.path,
                "starting_time": {"nanoseconds_since_epoch": f.start},
                "duration": {"nanoseconds": f.duration},
                "message_count": f.count,
            }
            for f in self.files
        ]
        info["custom_data"] = dict(self.custom_data) or None
        info["ros_distro"] = ROS_DISTRO
        return {"rosbag2_bagfile_information": info}

    def to_yaml(self) -> str:
        """The document as YAML text."""
        return yaml.safe_dump(self.to_dict(), sort_keys=False, default_flow_style=False)


def write_metadata(directory: Path, summary: BagSummary) -> Path:
    """Write ``DIR/metadata.yaml`` atomically (a reader never sees half a file)."""
    path = directory / METADATA_FILE
    temporary = path.with_suffix(".yaml.tmp")
    try:
        temporary.write_text(summary.to_yaml(), encoding="utf-8")
        os.replace(temporary, path)
    except OSError:
        temporary.unlink(missing_ok=True)  # a full disk: leave nothing half-written behind
        raise
    return path


def read_metadata(directory: Path) -> dict[str, Any]:
    """The ``rosbag2_bagfile_information`` mapping of a bag, checked for what info needs."""
    path = directory / METADATA_FILE
    if not directory.is_dir():
        raise BagError(f"{directory}: no such bag directory", expected="a rosbag2 bag directory")
    if not path.is_file():
        raise BagError(
            f"{path}: missing",
            expected="a rosbag2 bag directory",
            hint=f"a recorder that was killed leaves none: `launchkit bag reindex {directory}`",
        )
    try:
        document = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark is not None else str(path)
        raise BagError(f"{where}: not valid YAML: {getattr(exc, 'problem', exc)}") from None
    info = document.get("rosbag2_bagfile_information") if isinstance(document, dict) else None
    required = ("version", "storage_identifier", "duration", "starting_time", "message_count")
    if not isinstance(info, dict) or any(key not in info for key in required):
        raise BagError(
            f"{path}: not rosbag2 metadata",
            expected="a rosbag2_bagfile_information mapping with " + ", ".join(required),
        )
    return info
