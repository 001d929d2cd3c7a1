"""Our CDR bytes and type hashes against the real ROS 2 Jazzy rclpy (the PyPI wheels).

The ``test`` extra installs ``ros-jazzy-rclpy`` and ``ros-jazzy-common-interfaces`` where they
exist (CPython 3.11, Linux x86_64); elsewhere these tests skip with the reason.
"""

from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path
from typing import Any

import pytest

from launchkit.ros.message_data import fields_of
from launchkit.ros.msgs import deserialize, get_message, serialize, type_hash, type_names

try:
    from rclpy.serialization import deserialize_message, serialize_message
except ImportError as exc:  # pragma: no cover - depends on the platform
    pytest.skip(
        f"the real rclpy is not installed ({exc}); it needs CPython 3.11 on Linux x86_64",
        allow_module_level=True,
    )

# rclpy's type support imports lark, which imports the deprecated sre_parse
pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
_FILLER = "structure_needs_at_least_one_member"  # rosidl's field for types with none
SHARE = Path(sys.prefix) / "share"

# every type the stock nodes use
STOCK_TYPES = [
    "geometry_msgs/msg/Twist",
    "nav_msgs/msg/Odometry",
    "sensor_msgs/msg/JointState",
    "geometry_msgs/msg/TransformStamped",
    "sensor_msgs/msg/LaserScan",
    "sensor_msgs/msg/Image",
    "sensor_msgs/msg/CameraInfo",
    "rosgraph_msgs/msg/Clock",
    "std_msgs/msg/String",
]


def _official(kind: str) -> dict[str, str]:
    """type name -> the RIHS01 hash the wheels ship in share/<pkg>/<kind>/<Name>.json."""
    hashes: dict[str, str] = {}
    for path in sorted(SHARE.glob(f"*/{kind}/*.json")):
        for entry in json.loads(path.read_text())["type_hashes"]:
            hashes.setdefault(entry["type_name"], entry["hash_string"])
    return hashes


OFFICIAL_MSG = _official("msg")
OFFICIAL_SRV = _official("srv")


def _rclpy_class(type_name: str) -> Any:
    pkg, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), name)


def _populate(type_name: str, seed: int) -> dict[str, Any]:
    """Distinct, valid values for every field (nested as dicts)."""
    values: dict[str, Any] = {}
    for i, (name, desc) in enumerate(fields_of(type_name)):
        values[name] = 0 if name == _FILLER else _value(desc, seed + i)
    return values


def _value(desc: Any, seed: int) -> Any:
    kind, detail = desc
    if kind == _BASE:
        base, bound = detail
        if base == "bool":
            return seed % 2 == 0
        if base.startswith("float"):
            return seed + 0.5
        if base in ("string", "wstring"):
            text = f"s{seed}"
            return text[:bound] if bound else text
        if base == "byte":  # 1-byte bytes, in rclpy and launchkit
            return bytes([seed % 100])
        if base.startswith("int"):
            return -(seed % 100)
        return seed % 100
    if kind == _NAME:
        return ("msg", detail, _populate(detail, seed * 3 + 1))
    sub, length = detail
    count = length if kind == _ARRAY else min(2, length) if length else 2
    return [_value(sub, seed + j) for j in range(count)]


def _ours(type_name: str, values: dict[str, Any]) -> Any:
    cls = get_message(type_name)
    return cls(**{k: _to_ours(v) for k, v in values.items()})


def _to_ours(value: Any) -> Any:
    if isinstance(value, tuple):
        return _ours(value[1], value[2])
    if isinstance(value, list):
        return [_to_ours(v) for v in value]
    return value


def _theirs(type_name: str, values: dict[str, Any]) -> Any:
    msg = _rclpy_class(type_name)()
    for key, value in values.items():
        if key != _FILLER:
            setattr(msg, key, _to_theirs(value))
    return msg


def _to_theirs(value: Any) -> Any:
    if isinstance(value, tuple):
        return _theirs(value[1], value[2])
    if isinstance(value, list):
        return [_to_theirs(v) for v in value]
    return value


_SIZES = {
    "bool": 1,
    "byte": 1,
    "char": 1,
    "int8": 1,
    "uint8": 1,
    "int16": 2,
    "uint16": 2,
    "int32": 4,
    "uint32": 4,
    "float32": 4,
    "int64": 8,
    "uint64": 8,
    "float64": 8,
}


def _padding(msg: Any, type_name: str) -> tuple[set[int], int]:
    """Byte positions (after the 4-byte header) that CDR alignment fills in ``msg``, and how
    many empty sequences of 8-byte numbers it has.

    Fast CDR leaves padding uninitialised, so only the other bytes must equal rclpy's; and it
    sizes its buffer as if each empty 8-byte sequence were aligned, leaving up to 4 bytes of
    junk after the message for each.
    """
    pad: set[int] = set()
    pos = 0
    empty_wide = 0

    def align(size: int) -> None:
        nonlocal pos
        while pos % size:
            pad.add(pos)
            pos += 1

    def write(desc: Any, value: Any) -> None:
        nonlocal pos, empty_wide
        kind, detail = desc
        if kind == _BASE:
            base = detail[0]
            if base in ("string", "wstring"):
                align(4)
                pos += 4 + len(value.encode()) + 1
            else:
                align(_SIZES[base])
                pos += _SIZES[base]
        elif kind == _NAME:
            struct(value, detail)
        else:
            if kind == _SEQUENCE:
                align(4)
                pos += 4
                sub_kind, sub_detail = detail[0]
                if len(value) == 0 and sub_kind == _BASE and _SIZES.get(sub_detail[0]) == 8:
                    empty_wide += 1
            for item in value:
                write(detail[0], item)

    def struct(value: Any, name: str) -> None:
        fields = fields_of(name) or [("structure_needs_at_least_one_member", (_BASE, ("uint8", 0)))]
        for field, desc in fields:
            write(desc, getattr(value, field, 0))

    struct(msg, type_name)
    return pad, empty_wide


def _same_except_padding(ours: bytes, theirs: bytes, msg: Any, type_name: str) -> bool:
    """Our bytes equal rclpy's everywhere but in padding (which we zero) and its junk tail."""
    positions, empty_wide = _padding(msg, type_name)
    pad = {p + 4 for p in positions}
    if any(b for i, b in enumerate(ours) if i in pad):
        return False
    if not len(ours) <= len(theirs) <= len(ours) + 4 * empty_wide:
        return False
    return all(a == b for i, (a, b) in enumerate(zip(ours, theirs, strict=False)) if i not in pad)


COMMON_TYPES = sorted(
    name
    for name in OFFICIAL_MSG
    if name in type_names("msg") and not name.startswith("rmw_dds_common")
)


@pytest.mark.parametrize("type_name", STOCK_TYPES)
def test_stock_types_encode_byte_for_byte(type_name: str) -> None:
    values = _populate(type_name, 7)
    msg = _ours(type_name, values)
    ours = serialize(msg)
    theirs = serialize_message(_theirs(type_name, values))
    assert _same_except_padding(ours, theirs, msg, type_name)
    assert deserialize_message(ours, _rclpy_class(type_name)) == _theirs(type_name, values)
    assert deserialize(theirs, type_name) == deserialize(ours, type_name)


@pytest.mark.parametrize("type_name", STOCK_TYPES)
def test_stock_types_defaults_match_rclpy(type_name: str) -> None:
    msg = get_message(type_name)()
    ours, theirs = serialize(msg), serialize_message(_rclpy_class(type_name)())
    assert _same_except_padding(ours, theirs, msg, type_name)


def test_every_common_type_has_rclpys_defaults() -> None:
    different = [
        name
        for name in COMMON_TYPES
        if deserialize_message(serialize(get_message(name)()), _rclpy_class(name))
        != _rclpy_class(name)()
    ]
    assert different == []


def test_every_common_type_round_trips_through_rclpy() -> None:
    assert len(COMMON_TYPES) > 100
    mismatched = []
    for type_name in COMMON_TYPES:
        values = _populate(type_name, 3)
        ours = serialize(_ours(type_name, values))
        theirs_msg = _theirs(type_name, values)
        if deserialize_message(ours, _rclpy_class(type_name)) != theirs_msg:
            mismatched.append(type_name)
            continue
        decoded = deserialize(serialize_message(theirs_msg), type_name)
        if serialize(decoded) != ours:
            mismatched.append(type_name)
    assert mismatched == []


def test_jointstate_with_empty_trailing_array_from_fast_cdr() -> None:
    theirs = _rclpy_class("sensor_msgs/msg/JointState")(name=["a"], position=[1.0])
    decoded = deserialize(serialize_message(theirs), "sensor_msgs/msg/JointState")
    assert decoded.name == ["a"] and list(decoded.effort) == []


def test_message_hashes_match_the_official_ones() -> None:
    ours = {name: type_hash(name) for name in COMMON_TYPES}
    assert {n: h for n, h in ours.items() if h != OFFICIAL_MSG[n]} == {}
    assert "tf2_msgs/msg/TFMessage" not in OFFICIAL_MSG  # not in the wheels: see test_ros_msgs


def test_service_hashes_match_the_official_ones() -> None:
    services = sorted(
        name
        for name in OFFICIAL_SRV
        if "/srv/" in name
        and not name.endswith(("_Request", "_Response", "_Event"))
        and name in type_names("srv")
    )
    assert "std_srvs/srv/SetBool" in services and "rcl_interfaces/srv/SetParameters" in services
    wrong = {n: type_hash(n) for n in services if type_hash(n) != OFFICIAL_SRV[n]}
    assert wrong == {}
