"""CDR encoding and decoding of launchkit's message classes, generated once per type.

For each message type two Python functions are written and compiled the first time the type is
encoded or decoded: ``encode(out, msg)`` appends the message to a ``bytearray`` that starts with
the 4-byte encapsulation header, and ``decode(view, pos)`` reads one from a ``memoryview`` of the
payload (one per byte order). Runs of fixed-size fields are packed with one ``struct`` call,
alignment is computed when the code is written wherever the offset is known then, and nested
types call their own functions. The layout is Fast CDR's (XCDR1, as rmw_fastrtps and rmw_zenoh
write it): each primitive aligned to its size from the start of the payload, a sequence as a
``uint32`` count followed by its elements (aligned only when there is at least one), a string as
a ``uint32`` length including its NUL.

Decoded messages are instances of the same classes, made without running their constructors.
A numeric sequence is copied once, from the received bytes into its ``array.array`` (an
800x800 image is one 1.9 MB copy); a fixed-size numeric array is a new writable ``numpy`` array.
Bytes after the message are accepted: the DDS side pads some messages (an empty trailing
``float64[]``) where other encoders do not.
"""

from __future__ import annotations

import array
import struct
import threading
from collections.abc import Callable
from typing import Any

from rosbags.serde import SerdeError

from launchkit.ros.msgs import _spec as s
from launchkit.ros.msgs._codegen import NATIVE as _NATIVE
from launchkit.ros.msgs._codegen import DecoderWriter, EncoderWriter, function_name

HEADER_LEN = 4  # CDR encapsulation: 0x00, 0x01 (little endian) or 0x00 (big), two option bytes
_HEADER = bytes([0, 1 if _NATIVE == "<" else 0, 0, 0])

SpecOf = Callable[[str], s.MessageSpec]
ClassOf = Callable[[str], type]


class Codec:
    """Serializes and deserializes messages of one type (``pkg/msg/Name``)."""

    def __init__(self, type_name: str, functions: CodecFunctions) -> None:
        self.type_name = type_name
        self._functions = functions
        self._encode = functions.encoder(type_name)
        self._decode_native = functions.decoder(type_name, _NATIVE)

    def serialize(self, msg: Any) -> bytearray:
        """The CDR bytes of ``msg``, with the encapsulation header."""
        out = bytearray(_HEADER)
        try:
            self._encode(out, msg)
        except (struct.error, TypeError, ValueError, AttributeError, UnicodeEncodeError) as exc:
            raise SerdeError(f"Could not serialize {self.type_name!r}: {exc}") from exc
        return out

    def deserialize(self, data: bytes | bytearray | memoryview) -> Any:
        """The message in ``data`` (CDR with its header; bytes after the message are ignored)."""
        view = memoryview(data)
        if len(view) < HEADER_LEN or view[0] != 0 or view[1] > 1:
            raise SerdeError("Invalid or unsupported CDR encapsulation.")
        order = "<" if view[1] else ">"
        decode = (
            self._decode_native
            if order == _NATIVE
            else self._functions.decoder(self.type_name, order)
        )
        try:
            message, _ = decode(view[HEADER_LEN:], 0)
        except (struct.error, UnicodeDecodeError, ValueError, IndexError) as exc:
            raise SerdeError(f"Could not deserialize {self.type_name!r}: {exc}") from exc
        return message


class CodecFunctions:
    """The generated functions of every type, made on first use (thread-safe)."""

    def __init__(self, spec_of: SpecOf, class_of: ClassOf, check_fields: bool) -> None:
        self._spec_of = spec_of
        self._class_of = class_of
        self._check_fields = check_fields
        self._encoders: dict[str, Callable[[bytearray, Any], None]] = {}
        self._decoders: dict[tuple[str, str], Callable[[memoryview, int], tuple[Any, int]]] = {}
        self._lock = threading.RLock()

    def encoder(self, type_name: str) -> Callable[[bytearray, Any], None]:
        """``encode(out, msg)`` of ``type_name``."""
        found = self._encoders.get(type_name)
        if found is None:
            with self._lock:
                spec = self._spec_of(type_name)
                writer = EncoderWriter(spec)
                source = writer.source()
                namespace = self._namespace(spec, _NATIVE, True, writer.fixed_arrays)
                found = _compile(source, "encode", namespace)
                self._encoders[type_name] = found
        return found

    def decoder(self, type_name: str, order: str) -> Callable[[memoryview, int], tuple[Any, int]]:
        """``decode(view, pos) -> (msg, pos)`` of ``type_name`` for byte order ``order``."""
        key = (type_name, order)
        found = self._decoders.get(key)
        if found is None:
            with self._lock:
                spec = self._spec_of(type_name)
                writer = DecoderWriter(spec, order)
                source = writer.source()
                namespace = self._namespace(spec, order, False, writer.fixed_arrays)
                namespace["CLS"] = self._class_of(type_name)
                found = _compile(source, "decode", namespace)
                self._decoders[key] = found
        return found

    def _namespace(
        self, spec: s.MessageSpec, order: str, encode: bool, fixed_arrays: bool
    ) -> dict[str, Any]:
        namespace: dict[str, Any] = {
            "array": array.array,
            "struct": struct,
            "CHECK": self._check_fields,
            "U32": struct.Struct(order + "I"),
            "ZERO": bytes(8),
            "SWAP": order != _NATIVE,
        }
        if fixed_arrays:  # numpy, for the types that have them only (see _fixed_arrays)
            from launchkit.ros.msgs import _fixed_arrays

            namespace["bytes_of"] = _fixed_arrays.bytes_of
            namespace["fixed_array"] = _fixed_arrays.from_wire
        for ref in s.referenced_types(spec):
            key = function_name(ref)
            # nested types first (a message never contains itself, at any depth)
            if encode:
                namespace["enc_" + key] = self.encoder(ref)
            else:
                namespace["dec_" + key] = self.decoder(ref, order)
        return namespace


def _compile(source: str, name: str, namespace: dict[str, Any]) -> Any:
    exec(compile(source, f"<launchkit CDR {name}>", "exec"), namespace)
    return namespace[name]
