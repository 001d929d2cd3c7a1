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
import sys
import threading
from collections.abc import Callable
from typing import Any

import numpy
from rosbags.serde import SerdeError

from launchkit.ros.msgs import _spec as s
from launchkit.ros.msgs import definition as d

HEADER_LEN = 4  # CDR encapsulation: 0x00, 0x01 (little endian) or 0x00 (big), two option bytes
_NATIVE = "<" if sys.byteorder == "little" else ">"
_HEADER = bytes([0, 1 if _NATIVE == "<" else 0, 0, 0])
_STRUCT_CODES = {
    "boolean": "?",
    "octet": "c",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
    "float": "f",
    "double": "d",
}

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
                source = _EncoderWriter(spec).source()
                found = _compile(source, "encode", self._namespace(spec, _NATIVE, True))
                self._encoders[type_name] = found
        return found

    def decoder(self, type_name: str, order: str) -> Callable[[memoryview, int], tuple[Any, int]]:
        """``decode(view, pos) -> (msg, pos)`` of ``type_name`` for byte order ``order``."""
        key = (type_name, order)
        found = self._decoders.get(key)
        if found is None:
            with self._lock:
                spec = self._spec_of(type_name)
                source = _DecoderWriter(spec, order).source()
                namespace = self._namespace(spec, order, False)
                namespace["CLS"] = self._class_of(type_name)
                found = _compile(source, "decode", namespace)
                self._decoders[key] = found
        return found

    def _namespace(self, spec: s.MessageSpec, order: str, encode: bool) -> dict[str, Any]:
        namespace: dict[str, Any] = {
            "array": array.array,
            "numpy": numpy,
            "struct": struct,
            "CHECK": self._check_fields,
            "U32": struct.Struct(order + "I"),
            "ZERO": bytes(8),
            "SWAP": order != _NATIVE,
            "bytes_of": _bytes_of,
            "fixed_array": _fixed_array,
        }
        for ref in s.referenced_types(spec):
            key = _function_name(ref)
            # nested types first (a message never contains itself, at any depth)
            if encode:
                namespace["enc_" + key] = self.encoder(ref)
            else:
                namespace["dec_" + key] = self.decoder(ref, order)
        return namespace


def _compile(source: str, name: str, namespace: dict[str, Any]) -> Any:
    exec(compile(source, f"<launchkit CDR {name}>", "exec"), namespace)
    return namespace[name]


def _function_name(type_name: str) -> str:
    return type_name.replace("/", "__")


def _bytes_of(value: Any, dtype: Any, size: int) -> Any:
    """The bytes of a fixed-size numeric array of ``size`` elements (a buffer, not a copy)."""
    data = numpy.ascontiguousarray(value, dtype=dtype)
    if data.shape != (size,):
        raise ValueError(f"a fixed-size array of {size} values, got shape {data.shape}")
    return data.data


def _fixed_array(view: memoryview, dtype: Any, size: int, pos: int, native: Any) -> Any:
    return numpy.frombuffer(view, dtype=dtype, count=size, offset=pos).astype(native)


class _Writer:
    """Writes a function's lines, knowing the payload offset modulo ``known`` as ``residue``
    (``known == 1``: nothing known) so that padding is computed here where it can be."""

    def __init__(self, spec: s.MessageSpec) -> None:
        self.spec = spec
        self.lines: list[str] = []
        self.known, self.residue = 1, 0
        self.counter = 0

    def unknown(self) -> None:
        self.known, self.residue = 1, 0

    def advance(self, size: int) -> None:
        self.residue = (self.residue + size) % self.known

    def temp(self) -> str:
        self.counter += 1
        return f"t{self.counter}"


class _EncoderWriter(_Writer):
    """The source of ``encode(out, msg)``; the payload offset is ``len(out) - 4``."""

    def __init__(self, spec: s.MessageSpec) -> None:
        super().__init__(spec)
        self.group_format: list[str] = []
        self.group_values: list[str] = []

    def source(self) -> str:
        self.lines.append("def encode(out, msg):")
        for field in self.spec.fields:
            self.field(field)
        self.flush()
        self.lines.append("    return None")
        return "\n".join(self.lines) + "\n"

    def flush(self) -> None:
        if self.group_format:
            fmt = _NATIVE + "".join(self.group_format)
            self.lines.append(f"    out += struct.pack({fmt!r}, {', '.join(self.group_values)})")
            self.group_format, self.group_values = [], []

    def align(self, size: int) -> None:
        """Pad to ``size`` (into the current group when the padding is known now)."""
        if size <= self.known:
            pad = -self.residue % size
            if pad:
                self.group_format.append(f"{pad}x")
                self.advance(pad)
            return
        self.flush()
        self.lines.append(f"    out += ZERO[:(4 - len(out)) % {size}]")
        self.known, self.residue = size, 0

    def field(self, field: s.Field) -> None:
        value = f"msg._{field.name}"
        if field.name == d.EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME:
            value = "0"
        idl = s.idl_type(field.desc)
        if isinstance(idl, d.AbstractNestedType):
            self.nested(idl, value)
        else:
            self.scalar(idl, value, "    ")

    def scalar(self, idl: d.AbstractType, value: str, indent: str) -> None:
        if isinstance(idl, d.BasicType):
            size = struct.calcsize(_STRUCT_CODES[idl.typename])
            if indent == "    ":
                self.align(size)
                self.group_format.append(_STRUCT_CODES[idl.typename])
                self.group_values.append(value)
                self.advance(size)
                return
            code = _STRUCT_CODES[idl.typename]
            self.lines.append(f"{indent}out += ZERO[:(4 - len(out)) % {size}]")
            self.lines.append(f"{indent}out += struct.pack({_NATIVE + code!r}, {value})")
            return
        self.flush()
        if isinstance(idl, d.AbstractGenericString):
            if indent == "    ":
                self.align(4)
                self.flush()
            else:
                self.lines.append(f"{indent}out += ZERO[:(4 - len(out)) % 4]")
            temp = self.temp()
            self.lines.append(f"{indent}{temp} = {value}.encode()")
            self.lines.append(f"{indent}out += U32.pack(len({temp}) + 1)")
            self.lines.append(f"{indent}out += {temp}")
            self.lines.append(f"{indent}out.append(0)")
        else:
            assert isinstance(idl, d.NamespacedType)
            key = _function_name("/".join(idl.namespaced_name()))
            self.lines.append(f"{indent}enc_{key}(out, {value})")
        self.unknown()

    def nested(self, idl: d.AbstractNestedType, value: str) -> None:
        inner = idl.value_type
        special = s.special_typename(idl)
        if isinstance(idl, d.AbstractSequence):
            self.align(4)
            self.flush()
            count = self.temp()
            self.lines.append(f"    {count} = len({value})")
            self.lines.append(f"    out += U32.pack({count})")
        if special is not None:
            size = numpy.dtype(s.DTYPE_NAMES[special]).itemsize
            if isinstance(idl, d.Array):
                self.align(size)
                self.flush()
                dtype = _NATIVE + numpy.dtype(s.DTYPE_NAMES[special]).str[1:]
                self.lines.append(f"    out += bytes_of({value}, {dtype!r}, {idl.size})")
                self.advance(size * idl.size)
                return
            self.lines.append(f"    if {count}:")
            self.lines.append(f"        out += ZERO[:(4 - len(out)) % {size}]")
            self.lines.append(f"        out += {value}")
            self.unknown()
            return
        self.flush()
        if isinstance(inner, d.BasicType):
            code = _STRUCT_CODES[inner.typename]
            if inner.typename == d.OCTET_TYPE:
                self.lines.append(f"    out += b''.join({value})")
            else:
                size = struct.calcsize(code)
                if size > 1:
                    self.lines.append(f"    if {value}:")
                    self.lines.append(f"        out += ZERO[:(4 - len(out)) % {size}]")
                self.lines.append(
                    f"    out += struct.pack('{_NATIVE}%d{code}' % len({value}), *{value})"
                )
        else:
            item = self.temp()
            self.lines.append(f"    for {item} in {value}:")
            self.scalar(inner, item, "        ")
        self.unknown()


class _DecoderWriter(_Writer):
    """The source of ``decode(view, pos) -> (msg, pos)`` for one byte order."""

    def __init__(self, spec: s.MessageSpec, order: str) -> None:
        super().__init__(spec)
        self.order = order
        self.group_format: list[str] = []
        self.group_targets: list[str] = []

    def source(self) -> str:
        self.lines.append("def decode(view, pos):")
        self.lines.append("    msg = CLS.__new__(CLS)")
        self.lines.append("    msg._check_fields = CHECK")
        for field in self.spec.fields:
            self.field(field)
        self.flush()
        self.lines.append("    return msg, pos")
        return "\n".join(self.lines) + "\n"

    def flush(self) -> None:
        if self.group_format:
            fmt = self.order + "".join(self.group_format)
            size = struct.calcsize(fmt)
            if self.group_targets:
                targets = ", ".join(self.group_targets)
                self.lines.append(f"    ({targets},) = struct.unpack_from({fmt!r}, view, pos)")
            self.lines.append(f"    pos += {size}")
            self.group_format, self.group_targets = [], []

    def align(self, size: int) -> None:
        if size <= self.known:
            pad = -self.residue % size
            if pad:
                self.group_format.append(f"{pad}x")
                self.advance(pad)
            return
        self.flush()
        self.lines.append(f"    pos += -pos % {size}")
        self.known, self.residue = size, 0

    def field(self, field: s.Field) -> None:
        target = f"msg._{field.name}"
        if field.name == d.EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME:
            target = "_"
        idl = s.idl_type(field.desc)
        if isinstance(idl, d.AbstractNestedType):
            self.nested(idl, target)
        else:
            self.scalar(idl, target, "    ")

    def scalar(self, idl: d.AbstractType, target: str, indent: str) -> None:
        """Read one value into ``target`` (inside a loop: ``indent`` is deeper)."""
        if isinstance(idl, d.BasicType):
            code = _STRUCT_CODES[idl.typename]
            size = struct.calcsize(code)
            if indent == "    ":
                self.align(size)
                self.group_format.append(code)
                self.group_targets.append(target)
                self.advance(size)
                return
            self.lines.append(f"{indent}pos += -pos % {size}")
            self.lines.append(
                f"{indent}({target},) = struct.unpack_from({self.order + code!r}, view, pos)"
            )
            self.lines.append(f"{indent}pos += {size}")
            return
        if indent == "    ":
            self.align(4 if isinstance(idl, d.AbstractGenericString) else 1)
            self.flush()
        if isinstance(idl, d.AbstractGenericString):
            if indent != "    ":
                self.lines.append(f"{indent}pos += -pos % 4")
            length = self.temp()
            self.lines.append(f"{indent}({length},) = U32.unpack_from(view, pos)")
            self.lines.append(
                f"{indent}{target} = str(view[pos + 4 : pos + 3 + {length}], 'utf-8')"
            )
            self.lines.append(f"{indent}pos += 4 + {length}")
        else:
            assert isinstance(idl, d.NamespacedType)
            key = _function_name("/".join(idl.namespaced_name()))
            self.lines.append(f"{indent}{target}, pos = dec_{key}(view, pos)")
        if indent == "    ":
            self.unknown()

    def nested(self, idl: d.AbstractNestedType, target: str) -> None:
        inner = idl.value_type
        special = s.special_typename(idl)
        if isinstance(idl, d.Array):
            count = str(idl.size)
        else:
            self.align(4)
            self.flush()
            count = self.temp()
            self.lines.append(f"    ({count},) = U32.unpack_from(view, pos)")
            self.lines.append("    pos += 4")
            self.unknown()
        if special is not None:
            dtype = numpy.dtype(s.DTYPE_NAMES[special])
            size = dtype.itemsize
            if isinstance(idl, d.Array):
                self.align(size)
                self.flush()
                wire = self.order + dtype.str[1:]
                native = _NATIVE + dtype.str[1:]
                self.lines.append(
                    f"    {target} = fixed_array(view, {wire!r}, {count}, pos, {native!r})"
                )
                self.lines.append(f"    pos += {size * idl.size}")
                self.advance(size * idl.size)
                return
            values = self.temp()
            self.lines.append(f"    {values} = array({s.TYPE_CODES[special]!r})")
            self.lines.append(f"    if {count}:")
            self.lines.append(f"        pos += -pos % {size}")
            self.lines.append(f"        {values}.frombytes(view[pos : pos + {count} * {size}])")
            self.lines.append(f"        pos += {count} * {size}")
            self.lines.append("        if SWAP:")
            self.lines.append(f"            {values}.byteswap()")
            self.lines.append(f"    {target} = {values}")
            return
        self.flush()
        if isinstance(inner, d.BasicType) and inner.typename == d.OCTET_TYPE:
            self.lines.append(f"    {target} = [bytes((b,)) for b in view[pos : pos + {count}]]")
            self.lines.append(f"    pos += {count}")
        elif isinstance(inner, d.BasicType):
            code = _STRUCT_CODES[inner.typename]
            size = struct.calcsize(code)
            if size > 1:
                self.lines.append(f"    if {count}:")
                self.lines.append(f"        pos += -pos % {size}")
            unpack = f"struct.unpack_from('{self.order}%d{code}' % {count}, view, pos)"
            self.lines.append(f"    {target} = list({unpack})")
            self.lines.append(f"    pos += {count} * {size}")
        else:
            items, item = self.temp(), self.temp()
            self.lines.append(f"    {items} = []")
            self.lines.append(f"    for _ in range({count}):")
            self.scalar(inner, item, "        ")
            self.lines.append(f"        {items}.append({item})")
            self.lines.append(f"    {target} = {items}")
        self.unknown()
