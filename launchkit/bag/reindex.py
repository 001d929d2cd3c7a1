"""``launchkit bag reindex DIR``: rebuild ``metadata.yaml`` from a bag's storage files.

As ``ros2 bag reindex``, for a bag whose recorder died before writing its metadata. Beyond
rosbag2, an MCAP file that ends mid-record is first made readable (:mod:`mcap_repair`), a
sqlite3 file's unfinished transaction is rolled back, the file the recorder was writing gets its
split number, and in a bag of compressed files it is compressed like the others.
"""

from __future__ import annotations

import re
import sqlite3
import tempfile
from collections.abc import Callable
from pathlib import Path

from rosbags.interfaces import ConnectionExtRosbag2
from rosbags.rosbag2.storage_mcap import McapReader
from rosbags.rosbag2.storage_sqlite3 import Sqlite3Reader

from launchkit.bag import mcap_repair
from launchkit.bag.metadata import (
    METADATA_FILE,
    NO_MESSAGES,
    BagError,
    BagSummary,
    FileRecord,
    TopicRecord,
    write_metadata,
)
from launchkit.bag.storage import STORAGES, compress_file, decompress_file
from launchkit.errors import RuntimeLaunchError
from launchkit.ros.msgs import MessageTypeError, type_hash

_ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"
_NUMBERED = re.compile(r"_(\d+)$")
Log = Callable[[str], object]


def storage_files(path: Path) -> tuple[str, list[Path]]:
    """The bag's storage id and its files, in split order (an unnumbered file last)."""
    if not path.is_dir():
        raise BagError(f"{path}: no such bag directory", expected="a rosbag2 bag directory")
    found: dict[str, list[Path]] = {}
    for item in path.iterdir():
        if item.name.endswith(".tmp"):  # an interrupted file compression: its source remains
            item.unlink()
            continue
        for storage, suffix in STORAGES.items():
            if item.name.endswith((suffix, suffix + ".zstd")):
                found.setdefault(storage, []).append(item)
    if not found:
        raise BagError(f"{path}: no storage files", expected="*.mcap or *.db3 files")
    if len(found) > 1:
        raise BagError(f"{path}: both MCAP and sqlite3 files", expected="one storage kind")
    ((storage, files),) = found.items()
    names = {f.name for f in files}
    kept = []
    for file in files:
        if file.name + ".zstd" in names:  # killed between compressing it and removing it
            file.unlink()
        else:
            kept.append(file)
    return storage, sorted(kept, key=_split_index)


def _stem(path: Path) -> str:
    name = path.name.removesuffix(".zstd")
    return name.rsplit(".", 1)[0]


def _split_index(path: Path) -> tuple[int, str]:
    match = _NUMBERED.search(_stem(path))
    return (int(match.group(1)) if match else 1 << 62, path.name)


def _number_unnumbered(files: list[Path]) -> list[Path]:
    """Give the file the recorder was writing (``NAME.mcap``) the next split number."""
    numbered = [i for f in files if (i := _split_index(f)[0]) < 1 << 62]
    following = max(numbered, default=-1) + 1
    result = []
    for file in files:
        if not _NUMBERED.search(_stem(file)):
            target = file.with_name(f"{_stem(file)}_{following}{file.name[len(_stem(file)) :]}")
            file.rename(target)
            following += 1
            file = target
        result.append(file)
    return result


def _read_file(
    file: Path, name: str, storage: str, topics: dict[tuple[str, str], TopicRecord]
) -> tuple[FileRecord, bool]:
    """The span of one file (listed as ``name``); adds its topics to ``topics``.

    Also says whether its messages are zstd frames (``--compression-mode message``).
    """
    reader = McapReader(file) if storage == "mcap" else Sqlite3Reader(file)
    reader.open()
    try:
        meta = reader.metadata
        record = FileRecord(name)
        if meta.message_count:  # rosbags' end time is one past the last message
            record.start, record.end = meta.start_time, meta.end_time - 1
            record.count = meta.message_count
        for connection in reader.connections:
            ext = connection.ext
            if not isinstance(ext, ConnectionExtRosbag2):
                continue
            key = (connection.topic, connection.msgtype)
            if key not in topics:
                topics[key] = TopicRecord(
                    name=connection.topic,
                    type=connection.msgtype,
                    type_hash=connection.digest or _known_hash(connection.msgtype),
                    qos=ext.offered_qos_profiles,
                    serialization_format=ext.serialization_format,
                )
            topics[key].count += connection.msgcount
        first = next(iter(reader.messages(reader.connections)), None)
        return record, first is not None and bytes(first[2][:4]) == _ZSTD_MAGIC
    finally:
        reader.close()


def _known_hash(type_name: str) -> str:
    try:
        return type_hash(type_name)
    except (MessageTypeError, KeyError):
        return ""


def reindex(path: Path, log: Log = print) -> BagSummary:
    """Rebuild ``path/metadata.yaml``; repairs what a killed recorder left first. A full disk
    (or any other failure to write) is a :class:`RuntimeLaunchError`: every step replaces a
    file only once its new version is complete, so the bag is as it was before that step."""
    try:
        return _reindex(path, log)
    except OSError as error:
        where = f" ({error.filename})" if error.filename else ""
        raise RuntimeLaunchError(
            f"{path}: cannot reindex: {error.strerror or error}{where}",
            expected="room to write the repaired files and metadata.yaml",
            hint="nothing is half-written: free some space and run `launchkit bag reindex` again",
        ) from None


def _reindex(path: Path, log: Log) -> BagSummary:
    storage, files = storage_files(path)
    if storage == "sqlite3":  # before any rename: the journal is found by the file's name
        for file in files:
            if file.name.endswith(STORAGES[storage]):
                _roll_back(file)
    files = _number_unnumbered(files)
    compressed = any(f.name.endswith(".zstd") for f in files)
    summary = BagSummary(storage=storage)
    for index, file in enumerate(files):
        plain = file.name.endswith(STORAGES[storage])
        if storage == "mcap" and plain and not mcap_repair.is_complete(file):
            kept = mcap_repair.repair(file, summary.to_yaml())
            log(f"{file.name}: ended mid-record; kept its {kept} complete messages")
        if compressed and plain:
            file = compress_file(file)
            files[index] = file
    topics: dict[tuple[str, str], TopicRecord] = {}
    message_compression = False
    for file in files:
        if file.name.endswith(".zstd"):
            with tempfile.TemporaryDirectory() as scratch:
                plain_file = decompress_file(file, Path(scratch))
                record, zstd_messages = _read_file(plain_file, file.name, storage, topics)
        else:
            record, zstd_messages = _read_file(file, file.name, storage, topics)
        summary.files.append(record)
        message_compression |= zstd_messages
    summary.topics = list(topics.values())
    if compressed or message_compression:
        summary.compression_mode = "file" if compressed else "message"
        summary.compression_format = "zstd"
    write_metadata(path, summary)
    log(f"{path / METADATA_FILE}: {summary.message_count} messages in {len(files)} file(s)")
    if summary.start == NO_MESSAGES:
        log("the bag has no messages")
    return summary


def _roll_back(file: Path) -> None:
    """Open ``file`` read-write once, which rolls back a transaction its writer left open.

    A journal still there afterwards is one SQLite found nothing to roll back from (the writer
    was killed before it wrote its header); it would stay beside the renamed file, so it goes.
    """
    try:
        connection = sqlite3.connect(file)
        try:
            connection.execute("SELECT count(*) FROM messages").fetchone()
        finally:
            connection.close()
    except sqlite3.DatabaseError as exc:
        raise BagError(f"{file}: not a readable sqlite3 bag file: {exc}") from None
    file.with_name(file.name + "-journal").unlink(missing_ok=True)
