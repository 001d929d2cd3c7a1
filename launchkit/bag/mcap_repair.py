"""Making an MCAP file that ends mid-record (its writer was killed) readable again.

Such a file has no summary and no footer, so rosbags' reader refuses it. The ``mcap`` package's
stream reader reads it record by record up to the first incomplete one; every complete chunk
(and so every message up to the last flush) is written anew by rosbags' MCAP writer, which adds
the summary and footer. rosbags has no tolerant reader and the ``mcap`` package cannot append a
summary to a file, so this copy is the one piece done here.
"""

from __future__ import annotations

import os
import shutil
import struct
from dataclasses import dataclass, field
from pathlib import Path

from mcap.exceptions import McapError
from mcap.records import Channel, Chunk, McapRecord, Message, Schema
from mcap.stream_reader import StreamReader, breakup_chunk
from rosbags.interfaces import (
    Connection,
    ConnectionExtRosbag2,
    MessageDefinition,
    MessageDefinitionFormat,
)
from rosbags.rosbag2.enums import CompressionMode
from rosbags.rosbag2.errors import ReaderError
from rosbags.rosbag2.metadata import parse_qos
from rosbags.rosbag2.storage_mcap import McapReader, McapWriter

_FORMATS = {"ros2msg": MessageDefinitionFormat.MSG, "ros2idl": MessageDefinitionFormat.IDL}


def is_complete(path: Path) -> bool:
    """Whether rosbags reads ``path`` as it is (it has its footer)."""
    reader = McapReader(path)
    try:
        reader.open()
    except (ReaderError, OSError, struct.error, ValueError):
        return False
    reader.close()
    return True


@dataclass
class _Copy:
    """The state of one copy: what was declared in the new file, and how much."""

    writer: McapWriter
    schemas: dict[int, Schema] = field(default_factory=dict)
    declared_types: set[str] = field(default_factory=set)
    connections: dict[int, Connection] = field(default_factory=dict)
    messages: int = 0

    def record(self, record: McapRecord) -> None:
        if isinstance(record, Schema):
            self.schemas[record.id] = record
        elif isinstance(record, Channel):
            self._channel(record)
        elif isinstance(record, Message) and record.channel_id in self.connections:
            self.writer.write(self.connections[record.channel_id], record.log_time, record.data)
            self.messages += 1

    def _channel(self, channel: Channel) -> None:
        schema = self.schemas.get(channel.schema_id)
        if schema is None or channel.id in self.connections:
            return
        qos_text = channel.metadata.get("offered_qos_profiles", "")
        connection = Connection(
            id=channel.id,
            topic=channel.topic,
            msgtype=schema.name,
            msgdef=MessageDefinition(
                _FORMATS.get(schema.encoding, MessageDefinitionFormat.NONE),
                schema.data.decode(),
            ),
            digest="",
            msgcount=0,
            ext=ConnectionExtRosbag2(channel.message_encoding, parse_qos(qos_text)),
            owner=None,
        )
        if schema.name not in self.declared_types:
            self.writer.add_msgtype(connection)
            self.declared_types.add(schema.name)
        self.writer.add_connection(connection, qos_text)
        self.connections[channel.id] = connection


def _compressed_chunks(path: Path) -> bool:
    """Whether the file's chunks are compressed (looked at until the first chunk)."""
    with path.open("rb") as stream:
        try:
            for record in StreamReader(stream, emit_chunks=True).records:
                if isinstance(record, Chunk):
                    return bool(record.compression)
        except (McapError, struct.error, EOFError, ValueError):
            pass
    return False


def repair(path: Path, metadata: str) -> int:
    """Rewrite ``path`` with every complete record of it; the number of messages kept.

    ``metadata`` is the rosbag2 metadata text the new file embeds (as rosbag2's MCAP plugin).
    """
    mode = CompressionMode.STORAGE if _compressed_chunks(path) else CompressionMode.NONE
    scratch = path.with_name(f".{path.name}.reindex")
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir()
    try:
        copy = _Copy(McapWriter(scratch, mode))
        with path.open("rb") as stream:
            try:
                for record in StreamReader(stream, emit_chunks=True).records:
                    if isinstance(record, Chunk):
                        for inner in breakup_chunk(record):
                            copy.record(inner)
                    else:
                        copy.record(record)
            except (McapError, struct.error, EOFError, ValueError):
                pass  # the first incomplete record: everything before it is kept
        copy.writer.close(9, metadata)
        os.replace(copy.writer.path, path)
        return copy.messages
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
