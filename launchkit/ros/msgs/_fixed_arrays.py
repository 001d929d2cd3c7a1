"""Fixed-size numeric arrays (``float64[36]``), which rosidl's Python holds as ``numpy.ndarray``.

This is the only module of the message layer that imports numpy. Its users import it when a
value of such a field is first made, or a type that has one first coded; not when the message
layer loads, nor when such a type is made: importing numpy costs about 0.25 s of CPU, 40 % of a
node's start-up, and most nodes (tf, joint states, strings, parameters) never hold such a value
(``docs/benchmarks.md``, "Messages and nodes in a fresh process").
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy

from launchkit.ros.msgs import _spec as s


def _dtype(special: str) -> numpy.dtype[Any]:
    return numpy.dtype(s.dtype_code(special))  # native byte order: "f8" is float64


def converter(special: str) -> Callable[[Any], Any]:
    """What a setter stores for a value assigned to an array of ``special`` numbers."""
    dtype = _dtype(special)
    return lambda value: numpy.array(value, dtype=dtype)


def zeros(special: str, size: int) -> Callable[[], Any]:
    """The default of an array of ``size`` ``special`` numbers (a new array on every call)."""
    dtype = _dtype(special)
    return lambda: numpy.zeros(size, dtype=dtype)


def of_values(special: str, values: tuple[Any, ...]) -> Callable[[], Any]:
    """A ``.msg`` default of an array of ``special`` numbers (a new array on every call)."""
    dtype = _dtype(special)
    return lambda: numpy.array(values, dtype=dtype)


def kept_as_is(name: str, special: str, size: int) -> Callable[[Any], bool]:
    """With checks on: True for an ndarray of the right dtype and size (kept as it is);
    rosidl's ``AssertionError`` for an ndarray of another dtype or size."""
    dtype = _dtype(special)

    def keep(value: Any) -> bool:
        if not isinstance(value, numpy.ndarray):
            return False
        if value.dtype != dtype:
            raise AssertionError(
                f"The '{name}' numpy.ndarray() must have the dtype of 'numpy.{dtype.name}'"
            )
        if value.size != size:
            raise AssertionError(f"The '{name}' numpy.ndarray() must have a size of {size}")
        return True

    return keep


def bytes_of(value: Any, dtype: str, size: int) -> Any:
    """The bytes of a fixed-size numeric array of ``size`` elements (a buffer, not a copy)."""
    data = numpy.ascontiguousarray(value, dtype=dtype)
    if data.shape != (size,):
        raise ValueError(f"a fixed-size array of {size} values, got shape {data.shape}")
    return data.data


def from_wire(view: memoryview, dtype: str, size: int, pos: int, native: str) -> Any:
    """A new writable array of ``size`` elements read at ``pos`` in byte order ``dtype``."""
    return numpy.frombuffer(view, dtype=dtype, count=size, offset=pos).astype(native)
