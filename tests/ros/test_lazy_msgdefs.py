"""The typestore makes a type's host-order CDR functions when the type is first used and rosbags'
other ten (the other byte order, ROS 1) on their first call: the same bytes and messages as a
plain rosbags ``Typestore`` in every case."""

from __future__ import annotations

import sys
from typing import Any

import numpy as np
import pytest
from rosbags.typesys.store import Typestore

from launchkit.ros.msgs import _store as lazy
from launchkit.ros.msgs import type_names
from launchkit.ros.msgs._typestore import typestore, typestore_for

_HOST_IS_LITTLE = sys.byteorder == "little"


def _plain_copy(name: str, plain: Typestore) -> Any:
    """launchkit's typestore holding ``name``; ``plain``, a plain rosbags one, is given the
    same types (one plain store for a whole test: each type's code is generated once)."""
    mine = typestore_for(name)
    plain.fielddefs.update(mine.fielddefs)
    plain.types.update(mine.types)
    return mine


def _sample(store: Any, name: str) -> Any:
    """A message of ``name`` with every field at its default (arrays and sequences filled so that
    encoding has something to do)."""
    return store.types[name]()


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return bool(np.array_equal(a, b))
    if hasattr(a, "__dataclass_fields__"):
        return type(a) is type(b) and all(
            _same(getattr(a, f), getattr(b, f)) for f in a.__dataclass_fields__
        )
    if isinstance(a, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b)


def _outcome(store: Any, convert: str, data: bytes, name: str) -> tuple[str, Any]:
    """What ``store.<convert>(data, name)`` gives, or the error it raises (a ROS 2 message with
    a header is no valid ROS 1 data: both stores must refuse it alike)."""
    try:
        return "value", getattr(store, convert)(data, name)
    except Exception as error:
        return type(error).__name__, str(error)


def test_using_a_type_makes_none_of_the_other_functions(monkeypatch: pytest.MonkeyPatch) -> None:
    made: list[str] = []
    for generator in (
        "generate_serialize_ros1",
        "generate_deserialize_ros1",
        "generate_ros1_to_cdr",
        "generate_cdr_to_ros1",
    ):
        real = getattr(lazy, generator)
        monkeypatch.setattr(
            lazy,
            generator,
            lambda *args, _real=real, _name=generator, **kw: (
                made.append(_name),
                _real(*args, **kw),
            )[1],
        )
    name = "diagnostic_msgs/msg/DiagnosticArray"  # not used by another test of this process
    store = typestore_for(name)
    store.cache.pop(name, None)
    msgdef = store.get_msgdef(name)
    data = store.serialize_cdr(_sample(store, name), name)
    assert _same(store.deserialize_cdr(data, name), _sample(store, name))
    assert made == []
    msgdef.serialize_ros1(
        bytearray(msgdef.getsize_ros1(0, _sample(store, name), store)),
        0,
        _sample(store, name),
        store,
    )
    assert made and set(made) == {"generate_serialize_ros1"}  # for it and the types inside it


@pytest.mark.parametrize("kind", ["msg", "srv"])
def test_every_type_encodes_and_decodes_as_plain_rosbags_does(kind: str) -> None:
    if kind == "srv":
        store = typestore(services=True)
        names = [n for n in store.types if "/srv/" in n]
    else:
        names = type_names("msg")
    assert names
    plain = Typestore()
    for name in names:
        mine = _plain_copy(name, plain)
        message = _sample(mine, name)
        ours, theirs = mine.get_msgdef(name), plain.get_msgdef(name)
        assert ours.size_cdr == theirs.size_cdr and ours.size_ros1 == theirs.size_ros1, name
        for little in (True, False):
            cdr_ours = mine.serialize_cdr(message, name, little_endian=little)
            cdr_theirs = plain.serialize_cdr(message, name, little_endian=little)
            assert cdr_ours == cdr_theirs, (name, little)
            assert _same(mine.deserialize_cdr(cdr_ours, name), message), (name, little)
        ros1 = mine.serialize_ros1(message, name)
        assert ros1 == plain.serialize_ros1(message, name), name
        assert _same(mine.deserialize_ros1(ros1, name), message), name
        cdr = mine.serialize_cdr(message, name)
        for convert, data in (("cdr_to_ros1", cdr), ("ros1_to_cdr", ros1)):
            ours_out = _outcome(mine, convert, data, name)
            assert ours_out == _outcome(plain, convert, data, name), (name, convert)


def test_the_host_order_functions_are_made_up_front() -> None:
    name = "geometry_msgs/msg/PoseWithCovariance"
    store = typestore_for(name)
    store.cache.pop(name, None)
    msgdef = store.get_msgdef(name)
    host = msgdef.serialize_cdr_le if _HOST_IS_LITTLE else msgdef.serialize_cdr_be
    other = msgdef.serialize_cdr_be if _HOST_IS_LITTLE else msgdef.serialize_cdr_le
    assert host.__name__ != "call"  # rosbags' generated function itself
    assert other.__name__ == "call"  # made on its first call
