"""rosbags' ``Typestore`` generating a type's CDR functions when the type is first used and the
others when first called.

rosbags makes thirteen functions per message type the first time it is used: CDR size, encode
and decode in both byte orders, and nine for ROS 1 (bags of ROS 1, converters). launchkit uses
three of them (size, encode and decode in the host's byte order); the ROS 1 ones and the other
byte order are rarely or never called. Generating all thirteen cost a process 30-40 ms of CPU
for an Odometry's ten types, and more for a node's parameter services. Here the other ten are
made on their first call, by rosbags' own generators, so what they return is unchanged.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from rosbags.interfaces import Msgdef
from rosbags.serde.cdr import generate_deserialize_cdr, generate_getsize_cdr, generate_serialize_cdr
from rosbags.serde.ros1 import (
    generate_cdr_to_ros1,
    generate_deserialize_ros1,
    generate_getsize_ros1,
    generate_ros1_to_cdr,
    generate_serialize_ros1,
)
from rosbags.typesys.base import normalize_fieldname
from rosbags.typesys.store import Typestore

_HOST, _OTHER = ("le", "be") if sys.byteorder == "little" else ("be", "le")


def _on_first_call(make: Callable[[], Any]) -> Any:
    """A function that makes the real one with ``make`` on its first call, then calls it."""
    made: list[Any] = []

    def call(*args: Any) -> Any:
        if not made:
            made.append(make())
        return made[0](*args)

    return call


def _both_orders(make: Callable[[str], Any]) -> tuple[Any, Any]:
    """(little-endian, big-endian) functions from ``make(order)``: the host's made now, the
    other on its first call."""
    made, later = make(_HOST), _on_first_call(lambda: make(_OTHER))
    return (made, later) if _HOST == "le" else (later, made)


class LazyTypestore(Typestore):
    """A ``Typestore`` whose message definitions make only the host's CDR functions up front."""

    def get_msgdef(self, typename: str) -> Msgdef[object]:
        """Retrieve the message definition of ``typename`` (made on first use)."""
        cached = self.cache.get(typename)
        if cached is not None:
            return cached
        entries = [(normalize_fieldname(name), desc) for name, desc in self.fielddefs[typename][1]]
        getsize_cdr, size_cdr = generate_getsize_cdr(entries, self)
        # its size is a plain number every definition must have: made now (it is cheap)
        getsize_ros1, size_ros1 = generate_getsize_ros1(entries, self)
        serialize_le, serialize_be = _both_orders(
            lambda order: generate_serialize_cdr(entries, self, order)
        )
        deserialize_le, deserialize_be = _both_orders(
            lambda order: generate_deserialize_cdr(entries, self, order)
        )
        msgdef: Msgdef[object] = Msgdef(
            typename,
            entries,
            self.types[typename],
            size_cdr,
            getsize_cdr,
            serialize_le,
            serialize_be,
            deserialize_le,
            deserialize_be,
            size_ros1,
            getsize_ros1,
            _on_first_call(lambda: generate_serialize_ros1(entries, self)),
            _on_first_call(lambda: generate_deserialize_ros1(entries, self)),
            _on_first_call(lambda: generate_ros1_to_cdr(entries, typename, self, copy=False)),
            _on_first_call(lambda: generate_ros1_to_cdr(entries, typename, self, copy=True)),
            _on_first_call(lambda: generate_cdr_to_ros1(entries, typename, self, copy=False)),
            _on_first_call(lambda: generate_cdr_to_ros1(entries, typename, self, copy=True)),
        )
        self.cache[typename] = msgdef
        return msgdef
