"""rmw_zenoh (Jazzy) wire conventions: key expressions, liveliness tokens, attachments, GIDs."""

from __future__ import annotations

import os
import struct
from dataclasses import dataclass

import xxhash

from launchkit.errors import UserError
from launchkit.ros.qos import QoSProfile

LIVELINESS_PREFIX = "@ros2_lv"
GID_LEN = 16
_ATTACHMENT = struct.Struct("<qqB")


class DomainIdError(UserError):
    """A ``ROS_DOMAIN_ID`` that is not a number in 0..232."""


def domain_id() -> int:
    """``ROS_DOMAIN_ID`` (0 when unset), validated."""
    text = os.environ.get("ROS_DOMAIN_ID", "").strip()
    if not text:
        return 0
    if not text.isdigit() or int(text) > 232:
        raise DomainIdError(f"invalid ROS_DOMAIN_ID {text!r}", expected="an integer 0..232")
    return int(text)


def dds_type_name(type_name: str) -> str:
    """``pkg/msg/Name`` -> ``pkg::msg::dds_::Name_`` (the form rmw_zenoh puts in keys)."""
    pkg, kind, name = type_name.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def ros_type_name(dds_name: str) -> str:
    """``pkg::msg::dds_::Name_`` -> ``pkg/msg/Name``."""
    parts = dds_name.split("::")
    if len(parts) == 4 and parts[2] == "dds_" and parts[3].endswith("_"):
        return f"{parts[0]}/{parts[1]}/{parts[3][:-1]}"
    return dds_name.replace("::", "/")


def topic_key(domain: int, fqn: str, type_name: str, type_hash: str) -> str:
    """The data key expression of a topic or service: ``<domain>/<name>/<type>/<hash>``."""
    return f"{domain}/{fqn.lstrip('/')}/{dds_type_name(type_name)}/{type_hash}"


def mangle(name: str) -> str:
    """Token mangling: every ``/`` becomes ``%``; an empty name is ``%``."""
    return name.replace("/", "%") if name else "%"


def demangle(name: str) -> str:
    """Undo :func:`mangle` (``%`` alone is the empty name)."""
    return "" if name == "%" else name.replace("%", "/")


def node_token(domain: int, zid: str, node_id: int, enclave: str, namespace: str, name: str) -> str:
    """The liveliness token announcing a node (``NN``)."""
    ns = "" if namespace == "/" else namespace
    return (
        f"{LIVELINESS_PREFIX}/{domain}/{zid}/{node_id}/{node_id}/NN/"
        f"{mangle(enclave if enclave != '/' else '')}/{mangle(ns)}/{name}"
    )


ENTITY_KINDS = ("MP", "MS", "SS", "SC")


def entity_token(
    domain: int,
    zid: str,
    node_id: int,
    entity_id: int,
    kind: str,
    enclave: str,
    namespace: str,
    node_name: str,
    fqn: str,
    type_name: str,
    type_hash: str,
    qos: QoSProfile,
) -> str:
    """The liveliness token of a publisher (MP), subscription (MS), server (SS), client (SC)."""
    ns = "" if namespace == "/" else namespace
    return (
        f"{LIVELINESS_PREFIX}/{domain}/{zid}/{node_id}/{entity_id}/{kind}/"
        f"{mangle(enclave if enclave != '/' else '')}/{mangle(ns)}/{node_name}/"
        f"{mangle(fqn)}/{dds_type_name(type_name)}/{type_hash}/{qos.to_keyexpr()}"
    )


@dataclass(frozen=True)
class Token:
    """A parsed liveliness token (a node when ``kind == "NN"``)."""

    key: str
    domain: int
    zid: str
    node_id: str
    entity_id: str
    kind: str
    enclave: str
    namespace: str
    node_name: str
    topic: str = ""
    type_name: str = ""
    type_hash: str = ""
    qos: QoSProfile | None = None

    @property
    def node_fqn(self) -> str:
        """``/ns/name`` of the node this token belongs to."""
        return f"{self.namespace.rstrip('/')}/{self.node_name}"

    @property
    def gid(self) -> bytes:
        """The entity's GID (what its attachments carry)."""
        return gid_of(self.key)


def parse_token(key: str) -> Token | None:
    """Parse a liveliness key expression; None if rmw_zenoh would reject it.

    The checks are rmw_zenoh 0.2.x's (``liveliness_utils.cpp:Entity::make(keyexpr)``): at least
    9 ``/`` parts for a node and 13 for an entity, none empty, the ``@ros2_lv`` prefix, a known
    kind, a numeric domain and a valid QoS string; node and entity ids are any text.
    """
    parts = key.split("/")
    if len(parts) < 9 or parts[0] != LIVELINESS_PREFIX or not all(parts):
        return None
    if not parts[1].isascii() or not parts[1].isdigit():
        return None
    kind = parts[5]
    common = dict(
        key=key,
        domain=int(parts[1]),
        zid=parts[2],
        node_id=parts[3],
        entity_id=parts[4],
        kind=kind,
        enclave=demangle(parts[6]) or "/",
        namespace=demangle(parts[7]) or "/",
        node_name=demangle(parts[8]),
    )
    if kind == "NN":
        return Token(**common)  # type: ignore[arg-type]
    if kind not in ENTITY_KINDS or len(parts) < 13:
        return None
    try:
        qos = QoSProfile.from_keyexpr(parts[12])
    except UserError:
        return None
    return Token(
        **common,  # type: ignore[arg-type]
        topic=demangle(parts[9]),
        type_name=ros_type_name(demangle(parts[10])),
        type_hash=demangle(parts[11]),
        qos=qos,
    )


def gid_of(token_key: str) -> bytes:
    """An entity's GID: XXH3-128 of its token key, low 64 bits then high 64 bits (LE)."""
    h = xxhash.xxh3_128_intdigest(token_key.encode())
    return (h & 0xFFFFFFFFFFFFFFFF).to_bytes(8, "little") + (h >> 64).to_bytes(8, "little")


def encode_attachment(sequence: int, timestamp_ns: int, gid: bytes) -> bytes:
    """The 33-byte attachment: int64 sequence, int64 timestamp, length byte 16, GID."""
    return _ATTACHMENT.pack(sequence, timestamp_ns, GID_LEN) + gid


@dataclass(frozen=True)
class Attachment:
    """A decoded attachment."""

    sequence: int
    timestamp_ns: int
    gid: bytes


def decode_attachment(data: bytes | None) -> Attachment | None:
    """Decode the positional 33/32-byte form or the labelled form of Jazzy 0.2.0-0.2.3."""
    if not data:
        return None
    if len(data) == 33 and data[16] == GID_LEN:
        seq, ts, _ = _ATTACHMENT.unpack_from(data)
        return Attachment(seq, ts, bytes(data[17:]))
    if len(data) == 32:
        seq, ts = struct.unpack_from("<qq", data)
        return Attachment(seq, ts, bytes(data[16:]))
    return _decode_labelled(data)


def _decode_labelled(data: bytes) -> Attachment | None:
    # zenoh-ext serialization of (str, i64, str, i64, str, bytes): each str/bytes has a
    # LEB128 length prefix
    values: list[bytes | int] = []
    pos = 0
    try:
        for kind in ("s", "i", "s", "i", "s", "b"):
            if kind == "i":
                values.append(struct.unpack_from("<q", data, pos)[0])
                pos += 8
                continue
            length, shift = 0, 0
            while True:
                byte = data[pos]
                pos += 1
                length |= (byte & 0x7F) << shift
                shift += 7
                if byte < 0x80:
                    break
            values.append(bytes(data[pos : pos + length]))
            pos += length
    except (IndexError, struct.error):
        return None
    seq, ts, gid = values[1], values[3], values[5]
    if not isinstance(seq, int) or not isinstance(ts, int) or not isinstance(gid, bytes):
        return None
    return Attachment(seq, ts, gid)
