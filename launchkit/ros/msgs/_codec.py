"""CDR encoding and decoding of one message type, with nothing looked up or copied per message.

rosbags' ``Typestore.serialize_cdr`` / ``deserialize_cdr`` find the type's generated functions
on every call, and the decoder slices its ``bytes`` input past the 4-byte encapsulation header,
which copies the whole message (1.9 MB for an 800x800 camera image). A :class:`Codec` looks the
functions up once, writes into one ``bytearray`` that is handed to Zenoh as it is, and decodes
from a ``memoryview`` of the received bytes (numeric arrays are views of them, read-only, as
before).
"""

from __future__ import annotations

import functools
import struct
import sys
from typing import Any

from rosbags.serde import SerdeError

from launchkit.ros.msgs._typestore import typestore_for

HEADER_LEN = 4  # CDR encapsulation: 0x00, 0x01 (little endian) or 0x00 (big), two option bytes
_LITTLE = sys.byteorder == "little"  # rosbags' choice, and rmw's: the host's byte order


class Codec:
    """Serializes and deserializes messages of one type (``pkg/msg/Name``)."""

    def __init__(self, type_name: str) -> None:
        self.type_name = type_name
        self._store = typestore_for(type_name)
        msgdef = self._store.get_msgdef(type_name)
        self._cls = msgdef.cls
        self._size = msgdef.getsize_cdr
        self._write = msgdef.serialize_cdr_le if _LITTLE else msgdef.serialize_cdr_be
        self._read_le = msgdef.deserialize_cdr_le
        self._read_be = msgdef.deserialize_cdr_be

    def serialize(self, msg: Any) -> bytearray:
        """The CDR bytes of ``msg``, with the encapsulation header."""
        buffer = bytearray(HEADER_LEN + self._size(0, msg, self._store))
        buffer[1] = 1 if _LITTLE else 0
        self._write(memoryview(buffer)[HEADER_LEN:], 0, msg, self._store)
        return buffer

    def deserialize(self, data: bytes | bytearray | memoryview) -> Any:
        """The message in ``data`` (CDR with its header).

        Bytes after the message are accepted: Fast CDR pads before an empty trailing 8-byte
        sequence, which makes rosbags' own size check reject a valid message.
        """
        view = memoryview(data)
        if len(view) < HEADER_LEN or view[0] != 0 or view[1] > 1:
            raise SerdeError("Invalid or unsupported CDR encapsulation.")
        read = self._read_le if view[1] else self._read_be
        try:
            message, _ = read(view[HEADER_LEN:], 0, self._cls, self._store)
        except (struct.error, UnicodeDecodeError, ValueError) as exc:
            raise SerdeError(f"Could not deserialize {self.type_name!r}: {exc}") from exc
        return message


@functools.cache
def codec(type_name: str) -> Codec:
    """The (shared) codec of ``type_name``."""
    return Codec(type_name)
