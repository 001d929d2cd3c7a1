"""launchkit's message classes against rosidl's generated Python (the ros-jazzy wheels).

Two sets of types: every built-in type the wheels also have (std_msgs, geometry_msgs, ...,
their services), and ``test_msgs`` (its wheel ships both the interface files and rosidl's classes),
which launchkit reads *from its files* as it reads a user's package: defaults, constants,
bounded strings and sequences, fixed arrays, nested types, services and actions. Compared:
``repr``, ``get_fields_and_field_types``, ``SLOT_TYPES``, ``__slots__``, constants and
``NAME__DEFAULT`` values, the error (type and words) of every assignment rosidl's checks refuse,
the stored types of every one they accept, ``==``, CDR bytes both ways and RIHS01 hashes.
"""

from __future__ import annotations

import array
import functools
import importlib
import json
import math
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy
import pytest

from launchkit.packages import PackageIndex
from launchkit.ros.msgs import type_names
from launchkit.ros.msgs._registry import Registry

try:
    from rclpy.serialization import deserialize_message, serialize_message
    from rosidl_parser import definition as rosidl_definition
    from test_msgs.msg import BasicTypes  # noqa: F401 (the wheel's presence)
except ImportError as exc:  # pragma: no cover - depends on the platform
    pytest.skip(
        f"the ros-jazzy wheels (rclpy, test_msgs) are not installed ({exc}); they need "
        "CPython 3.11 on Linux x86_64",
        allow_module_level=True,
    )

pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

SHARE = Path(sys.prefix) / "share"
#: test_msgs read from its interface files, as a user's package is
FILES = Registry(PackageIndex(ament_prefix_path=sys.prefix, python_packages={}))
TEST_MSGS = [n for n in FILES.names("msg", {"test_msgs"}) if n.startswith("test_msgs/")]
TEST_SRVS = [n for n in FILES.names("srv", {"test_msgs"}) if n.startswith("test_msgs/")]
TEST_ACTIONS = [n for n in FILES.names("action", {"test_msgs"}) if n.startswith("test_msgs/")]


def real(type_name: str) -> Any:
    """rosidl's class of ``type_name`` from the wheels."""
    pkg, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), name)


def wheel_has(type_name: str) -> bool:
    try:
        real(type_name)
    except (ImportError, AttributeError):
        return False
    return True


BUILTIN_MSGS = [n for n in type_names("msg") if wheel_has(n)]
BUILTIN_SRVS = [n for n in type_names("srv") if wheel_has(n)]


def message_pairs() -> Iterator[tuple[str, Any, Any]]:
    """(name, ours, theirs) for every message class compared, services' parts included."""
    from launchkit.ros.msgs import get_message, get_service

    for name in BUILTIN_MSGS:
        yield name, get_message(name), real(name)
    for name in BUILTIN_SRVS:
        for part in ("Request", "Response", "Event"):
            yield f"{name}.{part}", getattr(get_service(name), part), getattr(real(name), part)
    for name in TEST_MSGS:
        yield name, FILES.message_class(name), real(name)
    for name in TEST_SRVS:
        for part in ("Request", "Response", "Event"):
            ours = getattr(FILES.service_class(name), part)
            yield f"{name}.{part}", ours, getattr(real(name), part)
    for name in TEST_ACTIONS:
        ours, theirs = FILES.action_class(name), real(name)
        for part in ("Goal", "Result", "Feedback"):
            yield f"{name}.{part}", getattr(ours, part), getattr(theirs, part)
        for part in ("SendGoalService", "GetResultService", "CancelGoalService"):
            for sub in ("Request", "Response", "Event"):
                yield (
                    f"{name}.Impl.{part}.{sub}",
                    getattr(getattr(ours.Impl, part), sub),
                    getattr(getattr(theirs.Impl, part), sub),
                )
        for part in ("FeedbackMessage", "GoalStatusMessage"):
            yield f"{name}.Impl.{part}", getattr(ours.Impl, part), getattr(theirs.Impl, part)


PAIRS = list(message_pairs())


def test_the_comparison_covers_the_common_types() -> None:
    assert len(BUILTIN_MSGS) > 140 and len(BUILTIN_SRVS) >= 25
    assert {"test_msgs/msg/Defaults", "test_msgs/msg/Strings", "test_msgs/msg/Arrays"} <= set(
        TEST_MSGS
    )
    assert TEST_ACTIONS == ["test_msgs/action/Fibonacci", "test_msgs/action/NestedMessage"]


def same_slot_type(ours: Any, theirs: Any) -> bool:
    """Our ``definition`` type describes what rosidl_parser's does."""
    if type(ours).__name__ != type(theirs).__name__:
        return False
    for attribute in ("typename", "name", "namespaces", "maximum_size", "size"):
        if hasattr(theirs, attribute) and getattr(ours, attribute) != getattr(theirs, attribute):
            return False
    if isinstance(theirs, rosidl_definition.AbstractNestedType):
        return same_slot_type(ours.value_type, theirs.value_type)
    return True


def class_constants(cls: Any) -> dict[str, str]:
    """Constants and ``NAME__DEFAULT`` values, read from the class and from an instance."""
    names = [n for n in dir(type(cls)) if n.isupper() or n.endswith("__DEFAULT")]
    names = [n for n in names if not n.startswith("_")]
    return {n: repr((getattr(cls, n), getattr(cls(), n), type(getattr(cls, n)))) for n in names}


@pytest.mark.parametrize(("name", "ours", "theirs"), PAIRS, ids=[p[0] for p in PAIRS])
def test_class_shape_and_defaults_are_rosidls(name: str, ours: Any, theirs: Any) -> None:
    assert repr(ours()) == repr(theirs())
    assert ours.get_fields_and_field_types() == theirs.get_fields_and_field_types()
    assert ours.__slots__ == theirs.__slots__
    assert len(ours.SLOT_TYPES) == len(theirs.SLOT_TYPES)
    assert all(map(same_slot_type, ours.SLOT_TYPES, theirs.SLOT_TYPES))
    assert class_constants(ours) == class_constants(theirs)
    assert (ours.__name__, type(ours).__name__) == (theirs.__name__, type(theirs).__name__)
    assert ours.__module__ == theirs.__module__
    for field in theirs.get_fields_and_field_types():
        mine, rosidls = getattr(ours(), field), getattr(theirs(), field)
        assert type(mine).__name__ == type(rosidls).__name__, field
        if isinstance(rosidls, numpy.ndarray):
            assert mine.dtype == rosidls.dtype, field
        if isinstance(rosidls, array.array):
            assert mine.typecode == rosidls.typecode, field


def candidate_values() -> list[Any]:
    """Values tried on every field: most are refused somewhere, with rosidl's words."""
    return [
        object(),
        None,
        "text",
        "t" * 30,
        "",
        0,
        1,
        -1,
        200,
        300,
        -300,
        70000,
        2**40,
        2**70,
        -(2**70),
        True,
        1.5,
        1e39,
        -1e39,
        1e309,
        math.inf,
        math.nan,
        b"x",
        b"xy",
        bytearray(b"z"),
        [],
        [1, 2, 3],
        [1, 2, 3, 4],
        [1.5, 2.5, 3.5],
        [-1, 0, 1],
        [300, 0, 0],
        [1e39, 0.0, 0.0],
        ["a", "b", "c"],
        ["t" * 30, "", ""],
        [b"a", b"b", b"c"],
        [True, False, True],
        (1, 2, 3),
        {1, 2, 3},
        numpy.zeros(3),
        numpy.zeros(3, dtype=numpy.float32),
        numpy.zeros(4),
        numpy.zeros(3, dtype=numpy.uint8),
        array.array("d", [1.0, 2.0, 3.0]),
        array.array("f", [1.0, 2.0]),
        array.array("i", [1, 2, 3, 4]),
        array.array("B", [1, 2]),
        array.array("q", [1]),
    ]


def outcome(make: Any) -> str:
    """What an action did: its error (type and words) or the stored value's type and repr."""
    try:
        value = make()
    except Exception as exc:
        return f"{type(exc).__name__}: {exc}"
    kind = type(value).__name__
    detail = value.dtype if isinstance(value, numpy.ndarray) else getattr(value, "typecode", "")
    return f"{kind} {detail} {value!r}"


CHECKED = [(name, ours, theirs) for name, ours, theirs in PAIRS if name.startswith("test_msgs/")]


@pytest.mark.parametrize(("name", "ours", "theirs"), CHECKED, ids=[p[0] for p in CHECKED])
def test_assignments_are_checked_with_rosidls_errors(name: str, ours: Any, theirs: Any) -> None:
    differences = []
    for field in theirs.get_fields_and_field_types():
        for value in candidate_values():
            mine = ours(check_fields=True)
            rosidls = theirs(check_fields=True)

            def set_mine(m: Any = mine, v: Any = value, f: str = field) -> Any:
                setattr(m, f, v)
                return getattr(m, f)

            def set_theirs(m: Any = rosidls, v: Any = value, f: str = field) -> Any:
                setattr(m, f, v)
                return getattr(m, f)

            got, expected = outcome(set_mine), outcome(set_theirs)
            if got != expected:
                differences.append((field, repr(value)[:40], got, expected))
    assert differences == []


def made_field(cls: Any, arguments: dict[str, Any], field: str) -> Any:
    """``field`` of ``cls(**arguments)``."""
    return getattr(cls(**arguments), field)


@pytest.mark.parametrize(("name", "ours", "theirs"), CHECKED, ids=[p[0] for p in CHECKED])
def test_constructor_is_rosidls(name: str, ours: Any, theirs: Any) -> None:
    differences = []
    for field in theirs.get_fields_and_field_types():
        for value in candidate_values():
            for check in (True, False):
                arguments = {"check_fields": check, field: value}
                got = outcome(functools.partial(made_field, ours, arguments, field))
                expected = outcome(functools.partial(made_field, theirs, arguments, field))
                if got != expected:
                    differences.append((field, check, repr(value)[:40], got, expected))
    assert differences == []
    assert outcome(lambda: ours(check_fields=True, no_such_field=1)) == outcome(
        lambda: theirs(check_fields=True, no_such_field=1)
    )


def test_equality_is_rosidls() -> None:
    from launchkit.ros.msgs import get_message

    ours, theirs = get_message("nav_msgs/msg/Odometry"), real("nav_msgs/msg/Odometry")
    for make in (ours, theirs):
        a, b = make(), make()
        assert a == b and not (a != b) and a != object()
        b.child_frame_id = "x"
        assert a != b
        c = make()
        c.pose.covariance[3] = 1.0
        assert a != c
    with pytest.raises(TypeError):
        hash(ours())


def test_repr_of_filled_sequences_and_arrays_is_rosidls() -> None:
    values: dict[str, Any] = {
        "name": ["j1", "j2"],
        "position": [1.0, 2.5],
        "velocity": array.array("d", [3.0]),
    }
    from launchkit.ros.msgs import get_message

    ours = get_message("sensor_msgs/msg/JointState")(**values)
    assert repr(ours) == repr(real("sensor_msgs/msg/JointState")(**values))
    covariance = {"covariance": [float(i) for i in range(36)]}
    ours_pose = get_message("geometry_msgs/msg/PoseWithCovariance")(**covariance)
    assert repr(ours_pose) == repr(real("geometry_msgs/msg/PoseWithCovariance")(**covariance))


def filled(cls: Any, seed: int) -> dict[str, Any]:
    """Distinct valid values for every field of a test_msgs class (nested as dicts)."""
    values: dict[str, Any] = {}
    fields = zip(cls.get_fields_and_field_types(), cls.SLOT_TYPES, strict=True)
    for i, (field, slot) in enumerate(fields):
        values[field] = value_for(slot, seed + i, cls)
    return values


def value_for(slot: Any, seed: int, cls: Any) -> Any:
    if isinstance(slot, rosidl_definition.AbstractNestedType):
        count = slot.size if isinstance(slot, rosidl_definition.Array) else 2
        if isinstance(slot, rosidl_definition.BoundedSequence):
            count = min(count, slot.maximum_size)
        return [value_for(slot.value_type, seed + j, cls) for j in range(count)]
    if isinstance(slot, rosidl_definition.NamespacedType):
        return ("msg", "/".join(slot.namespaced_name()), seed)
    if isinstance(slot, rosidl_definition.AbstractGenericString):
        text = f"s{seed}"
        return text[: slot.maximum_size] if slot.has_maximum_size() else text
    typename = slot.typename
    if typename == "boolean":
        return seed % 2 == 0
    if typename == "octet":
        return bytes([seed % 256])
    if typename in ("float", "double"):
        return seed + 0.5
    if typename.startswith("int"):
        return -(seed % 100)
    return seed % 100


def build(cls_of: Any, cls: Any, values: dict[str, Any]) -> Any:
    def convert(value: Any) -> Any:
        if isinstance(value, tuple) and value[0] == "msg":
            nested = cls_of(value[1])
            return build(cls_of, nested, filled(real(value[1]), value[2]))
        if isinstance(value, list):
            return [convert(v) for v in value]
        return value

    return cls(**{k: convert(v) for k, v in values.items()})


def ours_class(type_name: str) -> Any:
    from launchkit.ros.msgs import get_message

    return (
        FILES.message_class(type_name)
        if type_name.startswith("test_msgs/")
        else get_message(type_name)
    )


ENCODED = [n for n in TEST_MSGS] + [f"{n}_Request" for n in TEST_SRVS]


@pytest.mark.parametrize("type_name", ENCODED)
def test_bytes_are_rclpys(type_name: str) -> None:
    theirs_cls = real(type_name)
    values = filled(theirs_cls, 5)
    ours = build(ours_class, ours_class(type_name), values)
    theirs = build(real, theirs_cls, values)
    ours_bytes = bytes(FILES.codec(type_name).serialize(ours))
    theirs_bytes = serialize_message(theirs)
    # Fast CDR leaves padding unwritten and sizes its buffer generously: every byte we write
    # is rclpy's, or padding (zero)
    assert len(ours_bytes) <= len(theirs_bytes)
    assert all(a == b or a == 0 for a, b in zip(ours_bytes, theirs_bytes, strict=False))
    assert deserialize_message(ours_bytes, theirs_cls) == theirs
    decoded = FILES.codec(type_name).deserialize(theirs_bytes)
    assert repr(decoded) == repr(ours) == repr(theirs)
    assert bytes(FILES.codec(type_name).serialize(decoded)) == ours_bytes


def official_hashes(pkg: str) -> dict[str, str]:
    hashes: dict[str, str] = {}
    for path in sorted((SHARE / pkg).glob("*/*.json")):
        for entry in json.loads(path.read_text())["type_hashes"]:
            hashes[entry["type_name"]] = entry["hash_string"]
    return hashes


def test_hashes_of_interfaces_read_from_files_are_rosidls() -> None:
    expected = {
        name: value
        for name, value in official_hashes("test_msgs").items()
        if name.startswith("test_msgs/") and "WStrings" not in name
    }
    assert len(expected) > 40 and "test_msgs/action/Fibonacci_SendGoal_Event" in expected
    ours = {name: FILES.type_hash(name) for name in expected}
    assert ours == expected


def test_action_hashes_of_built_in_types_are_rosidls() -> None:
    from launchkit.ros.msgs import type_hash

    for name, value in official_hashes("action_msgs").items():
        assert type_hash(name) == value, name
