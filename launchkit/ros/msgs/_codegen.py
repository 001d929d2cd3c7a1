"""The Python source of one message type's CDR encoder and decoder (see :mod:`._codec`).

A writer walks the type's fields and emits code, knowing the payload offset modulo ``known`` as
``residue`` wherever it can: runs of fixed-size fields become one ``struct`` call with their
padding computed here, and only where the offset depends on the data (after a string or a
sequence, at the start of a nested type) is padding computed when the code runs. Nested types
call their own functions (``enc_pkg__msg__Name``, ``dec_...``), which the namespace provides.
"""

from __future__ import annotations

import struct
import sys

from launchkit.ros.msgs import _spec as s
from launchkit.ros.msgs import definition as d

NATIVE = "<" if sys.byteorder == "little" else ">"
# struct's codes are array's type codes for numbers (and sizes agree for the standard sizes)
_STRUCT_CODES = {**s.TYPE_CODES, "boolean": "?", "octet": "c"}


def function_name(type_name: str) -> str:
    """The part of a nested type's function names after ``enc_`` / ``dec_``."""
    return type_name.replace("/", "__")


class _Writer:
    """Writes a function's lines, knowing the payload offset modulo ``known`` as ``residue``
    (``known == 1``: nothing known) so that padding is computed here where it can be.

    Fixed-size fields gather in a group (``group_format``, one ``struct`` call) until
    :meth:`flush`; ``DUMMY`` is what stands for rosidl's one-byte member of an empty type.
    ``fixed_arrays`` says whether the code calls ``bytes_of`` or ``fixed_array`` (numpy)."""

    DUMMY = ""

    def __init__(self, spec: s.MessageSpec) -> None:
        self.spec = spec
        self.fixed_arrays = False
        self.lines: list[str] = []
        self.known, self.residue = 1, 0
        self.counter = 0
        self.group_format: list[str] = []

    def flush(self) -> None:
        raise NotImplementedError

    def pad_line(self, size: int) -> str:
        """The line that pads to ``size`` when the offset is only known at run time."""
        raise NotImplementedError

    def scalar(self, idl: d.AbstractType, name: str, indent: str) -> None:
        raise NotImplementedError

    def nested(self, idl: d.AbstractNestedType, name: str) -> None:
        raise NotImplementedError

    def align(self, size: int) -> None:
        """Pad to ``size`` (into the current group when the padding is known now)."""
        if size <= self.known:
            pad = -self.residue % size
            if pad:
                self.group_format.append(f"{pad}x")
                self.advance(pad)
            return
        self.flush()
        self.lines.append(self.pad_line(size))
        self.known, self.residue = size, 0

    def field(self, field: s.Field) -> None:
        name = f"msg._{field.name}"
        if field.name == d.EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME:
            name = self.DUMMY
        idl = s.idl_type(field.desc)
        if isinstance(idl, d.AbstractNestedType):
            self.nested(idl, name)
        else:
            self.scalar(idl, name, "    ")

    def unknown(self) -> None:
        self.known, self.residue = 1, 0

    def advance(self, size: int) -> None:
        self.residue = (self.residue + size) % self.known

    def temp(self) -> str:
        self.counter += 1
        return f"t{self.counter}"


class EncoderWriter(_Writer):
    """The source of ``encode(out, msg)``; the payload offset is ``len(out) - 4``."""

    DUMMY = "0"

    def __init__(self, spec: s.MessageSpec) -> None:
        super().__init__(spec)
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
            fmt = NATIVE + "".join(self.group_format)
            self.lines.append(f"    out += struct.pack({fmt!r}, {', '.join(self.group_values)})")
            self.group_format, self.group_values = [], []

    def pad_line(self, size: int) -> str:
        return f"    out += ZERO[:(4 - len(out)) % {size}]"

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
            self.lines.append(f"{indent}out += struct.pack({NATIVE + code!r}, {value})")
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
            key = function_name("/".join(idl.namespaced_name()))
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
            size = s.item_size(special)
            if isinstance(idl, d.Array):
                self.align(size)
                self.flush()
                dtype = NATIVE + s.dtype_code(special)
                self.fixed_arrays = True
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
                    f"    out += struct.pack('{NATIVE}%d{code}' % len({value}), *{value})"
                )
        else:
            item = self.temp()
            self.lines.append(f"    for {item} in {value}:")
            self.scalar(inner, item, "        ")
        self.unknown()


class DecoderWriter(_Writer):
    """The source of ``decode(view, pos) -> (msg, pos)`` for one byte order."""

    DUMMY = "_"

    def __init__(self, spec: s.MessageSpec, order: str) -> None:
        super().__init__(spec)
        self.order = order
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

    def pad_line(self, size: int) -> str:
        return f"    pos += -pos % {size}"

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
            key = function_name("/".join(idl.namespaced_name()))
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
            size = s.item_size(special)
            if isinstance(idl, d.Array):
                self.align(size)
                self.flush()
                wire, native = self.order + s.dtype_code(special), NATIVE + s.dtype_code(special)
                self.fixed_arrays = True
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
