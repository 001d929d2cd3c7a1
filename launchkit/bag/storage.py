"""Writing a rosbag2 bag: rosbags' storage plugins, plus what rosbags' ``Writer`` lacks.

rosbags (``rosbags.rosbag2``) writes the storage files: MCAP (with zstd chunk compression) and
sqlite3. Its ``Writer`` makes one file per bag and writes nothing readable before ``close()``, so
launchkit drives the storage plugins itself and adds, by hand:

* **splitting** by size or duration into ``NAME_0.mcap``, ``NAME_1.mcap``... (rosbag2's names);
  rosbags' plugins always create ``NAME.mcap``, so a finished file is renamed;
* **file compression** per split file (``NAME_0.mcap.zstd``, rosbag2's ``--compression-mode
  file``) and **message compression** (``--compression-mode message``), both zstd;
* **durability**: the MCAP chunk is closed and flushed at least every ``flush_interval`` seconds
  (sqlite3: committed), so a recorder killed with SIGKILL loses only the last interval
  (``launchkit bag reindex`` then makes the bag readable);
* **metadata.yaml** for several files (:mod:`launchkit.bag.metadata`).
"""

from __future__ import annotations

import os
import shutil
import sys
import threading
import time
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import yaml
from rosbags.interfaces import (
    Connection,
    ConnectionExtRosbag2,
    MessageDefinition,
    MessageDefinitionFormat,
)
from rosbags.rosbag2.enums import CompressionMode
from rosbags.rosbag2.metadata import dump_qos_v9
from rosbags.rosbag2.storage_mcap import McapWriter
from rosbags.rosbag2.storage_sqlite3 import Sqlite3Writer

from launchkit.bag.metadata import BagError, BagSummary, FileRecord, TopicRecord, write_metadata

if sys.version_info >= (3, 14):
    from compression import zstd
else:
    from backports import zstd

STORAGES = {"mcap": ".mcap", "sqlite3": ".db3"}
COMPRESSION_MODES = ("none", "file", "message")
#: MCAP chunk compression presets (rosbag2_storage_mcap's names) and their zstd levels.
PRESETS = {"none": None, "zstd_fast": 1, "zstd_small": 19}


@dataclass(frozen=True)
class WriterOptions:
    """How a bag is written (rosbag2's recorder options of the same names)."""

    storage: str = "mcap"
    compression_mode: str = "none"
    storage_preset_profile: str = "none"
    max_bag_size: int = 0  # bytes of messages per file; 0: no split by size
    max_bag_duration: int = 0  # nanoseconds per file; 0: no split by duration
    flush_interval: float = 1.0  # seconds of messages a SIGKILL may lose at most
    custom_data: dict[str, str] = field(default_factory=dict)

    def check(self) -> None:
        """Raise :class:`BagError` for a combination rosbag2 refuses too."""
        if self.storage not in STORAGES:
            raise BagError(f"unknown storage {self.storage!r}", expected="mcap or sqlite3")
        if self.compression_mode not in COMPRESSION_MODES:
            raise BagError(
                f"unknown compression mode {self.compression_mode!r}",
                expected=", ".join(COMPRESSION_MODES),
            )
        if self.storage_preset_profile not in PRESETS:
            raise BagError(
                f"unknown storage preset profile {self.storage_preset_profile!r}",
                expected=", ".join(PRESETS),
            )
        if self.storage == "sqlite3" and self.storage_preset_profile != "none":
            raise BagError(
                "storage preset profiles are MCAP chunk compression; sqlite3 has none",
                expected="--compression-mode file or message with sqlite3",
            )
        if self.storage == "mcap" and self.compression_mode == "message":
            raise BagError(
                "MCAP storage does not support message compression (as rosbag2)",
                expected="--storage-preset-profile zstd_fast (chunks) or --compression-mode file",
            )
        if self.max_bag_size < 0 or self.max_bag_duration < 0:
            raise BagError("split limits must not be negative", expected="0 (off) or more")


@dataclass
class BagTopic:
    """A topic of the bag being written: its storage connection and its record."""

    record: TopicRecord
    connection: Connection


class BagWriter:
    """Writes a bag directory; one thread at a time (the recorder's writer thread)."""

    def __init__(self, path: Path, options: WriterOptions) -> None:
        options.check()
        if path.exists():
            raise BagError(f"Output folder '{path}' already exists.", expected="a new folder")
        path.mkdir(parents=True)
        self.path = path
        self.options = options
        self.summary = BagSummary(
            storage=options.storage,
            compression_mode="" if options.compression_mode == "none" else options.compression_mode,
            compression_format="" if options.compression_mode == "none" else "zstd",
            custom_data=dict(options.custom_data),
        )
        self.topics: list[BagTopic] = []
        self._compressing: list[threading.Thread] = []
        self._storage: McapWriter | Sqlite3Writer | None = None
        self._file: FileRecord | None = None
        self._file_bytes = 0
        self._flushed_chunks = 0
        self._last_flush = time.monotonic()
        # the storage is opened by the first call of the writing thread: sqlite3 connections
        # belong to the thread that made them

    def _current(self) -> McapWriter | Sqlite3Writer:
        if self._storage is None:
            self._open_file()
        assert self._storage is not None
        return self._storage

    # files ------------------------------------------------------------------------------
    def _open_file(self) -> None:
        preset = PRESETS[self.options.storage_preset_profile]
        if self.options.storage == "mcap":
            mode = CompressionMode.STORAGE if preset is not None else CompressionMode.NONE
            mcap = McapWriter(self.path, mode)
            if preset is not None:
                # rosbags compresses chunks at zstd's default level; the preset picks its own
                mcap.compressor = partial(zstd.compress, level=preset)
            storage: McapWriter | Sqlite3Writer = mcap
        else:
            storage = Sqlite3Writer(self.path, CompressionMode.NONE)
        self._storage = storage
        index = len(self.summary.files)
        name = f"{self.path.name}_{index}{STORAGES[self.options.storage]}"
        if self.options.compression_mode == "file":
            name += ".zstd"
        self._file = FileRecord(name)
        self.summary.files.append(self._file)
        self._file_bytes = 0
        self._flushed_chunks = 0
        declared: set[str] = set()
        for topic in self.topics:  # a new split file declares every topic known so far
            if topic.record.type not in declared:
                storage.add_msgtype(topic.connection)
                declared.add(topic.record.type)
            storage.add_connection(topic.connection, yaml_qos(topic))

    def _close_file(self) -> None:
        storage, record = self._storage, self._file
        if storage is None or record is None:
            return
        self._storage = None
        storage.close(9, self.summary.to_yaml())
        final = self.path / record.path.removesuffix(".zstd")
        os.replace(storage.path, final)
        if self.options.compression_mode == "file":
            worker = threading.Thread(
                target=compress_file, args=(final,), name=f"compress {final.name}", daemon=True
            )
            worker.start()
            self._compressing.append(worker)

    def split(self) -> None:
        """Close the current file and go on in a new one."""
        self._close_file()
        self._open_file()

    # writing ----------------------------------------------------------------------------
    def add_topic(self, record: TopicRecord, msgdef: str) -> BagTopic:
        """Declare a topic (its type's definition is ``msgdef``, ros2msg text)."""
        connection = Connection(
            id=len(self.topics) + 1,
            topic=record.name,
            msgtype=record.type,
            msgdef=MessageDefinition(MessageDefinitionFormat.MSG, msgdef),
            digest=record.type_hash,
            msgcount=0,
            ext=ConnectionExtRosbag2(
                serialization_format=record.serialization_format,
                offered_qos_profiles=list(record.qos),
            ),
            owner=None,
        )
        topic = BagTopic(record, connection)
        storage = self._current()
        new_type = all(t.record.type != record.type for t in self.topics)
        self.topics.append(topic)
        self.summary.topics.append(record)
        if new_type:
            storage.add_msgtype(connection)
        storage.add_connection(connection, yaml_qos(topic))
        return topic

    def write(self, topic: BagTopic, timestamp: int, data: bytes) -> None:
        """Write one serialized message received at ``timestamp`` (ns since the epoch)."""
        storage = self._current()
        if self._file is not None and self._file.count and self._split_due(timestamp):
            self.split()
            storage = self._current()
        record = self._file
        assert record is not None
        if self.options.compression_mode == "message":
            data = zstd.compress(data)
        storage.write(topic.connection, timestamp, data)
        record.add(timestamp)
        topic.record.count += 1
        self._file_bytes += len(data)
        if isinstance(storage, McapWriter) and len(storage.chunks) != self._flushed_chunks:
            # rosbags closed a full chunk: hand it to the OS now, not when its buffer fills
            storage.bio.flush()
            self._flushed_chunks = len(storage.chunks)
        self.flush_if_due()

    def _split_due(self, timestamp: int) -> bool:
        options, record = self.options, self._file
        assert record is not None
        if options.max_bag_size and self._file_bytes >= options.max_bag_size:
            return True
        return bool(options.max_bag_duration) and timestamp - record.start >= (
            options.max_bag_duration
        )

    def flush_if_due(self) -> None:
        """Make what was written readable after a crash, at most every ``flush_interval``."""
        now = time.monotonic()
        if now - self._last_flush < self.options.flush_interval:
            return
        self._last_flush = now
        self.flush()

    def flush(self) -> None:
        """Close the pending MCAP chunk (if it holds messages) or commit sqlite3, and flush."""
        storage = self._storage
        if isinstance(storage, McapWriter):
            if storage.chunk.msgs:
                storage.close_chunk()
            storage.bio.flush()
            self._flushed_chunks = len(storage.chunks)
        elif isinstance(storage, Sqlite3Writer):
            storage.conn.commit()

    def close(self) -> BagSummary:
        """Finish the last file, wait for file compression, write ``metadata.yaml``."""
        self._current()  # a bag without messages still has its (empty) storage file
        self._close_file()
        for worker in self._compressing:
            worker.join()
        write_metadata(self.path, self.summary)
        return self.summary


def yaml_qos(topic: BagTopic) -> str:
    """The QoS text a storage file keeps per topic (rosbag2 version 9)."""
    profiles = dump_qos_v9(list(topic.record.qos))
    return yaml.safe_dump(profiles, sort_keys=False, default_flow_style=False).strip()


def compress_file(path: Path) -> Path:
    """Compress ``path`` to ``path.zstd`` (rosbag2's file compression), remove it; the result."""
    target = path.with_name(path.name + ".zstd")
    temporary = path.with_name(path.name + ".zstd.tmp")
    with path.open("rb") as source, zstd.open(temporary, "wb") as sink:
        shutil.copyfileobj(source, sink, 1 << 20)
    os.replace(temporary, target)
    path.unlink()
    return target


def decompress_file(path: Path, directory: Path) -> Path:
    """``FILE.zstd`` decompressed into ``directory`` as ``FILE``; the new file."""
    target = directory / path.name.removesuffix(".zstd")
    with zstd.open(path, "rb") as source, target.open("wb") as sink:
        shutil.copyfileobj(source, sink, 1 << 20)
    return target
