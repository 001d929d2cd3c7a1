"""One field of a message class: its property (getter and checking setter) and its default.

The checks and their messages are rosidl_generator_py's (Jazzy): they run only when the message
was made with ``check_fields=True`` or ``ROS_PYTHON_CHECK_FIELDS=1`` is set, as in rclpy, and
fail with ``AssertionError`` and rosidl's words. Whatever the checks, a numeric sequence is stored
as ``array.array`` and a fixed-size numeric array as ``numpy.ndarray``, as rosidl's setters do.

The fixed-size arrays' parts come from :mod:`._fixed_arrays`, imported when the first value of
such a field is made or stored: that module is what imports numpy (it says why not sooner).
"""

from __future__ import annotations

import array
import math
from collections import UserList, UserString
from collections.abc import Callable, Sequence, Set
from operator import attrgetter
from typing import Any

from launchkit.ros.msgs import _spec as s
from launchkit.ros.msgs import definition as d

FLOAT_BOUNDS = {"float": 3.402823466e38, "double": 1.7976931348623157e308}
_PY_TYPES: dict[str, type] = {"int": int, "float": float, "bool": bool, "bytes": bytes, "str": str}

Check = Callable[[Any], None]
ClassOf = Callable[[str], type]


def field_property(name: str, idl: d.AbstractType, class_of: ClassOf) -> property:
    """The property of field ``name``: reads ``_name``, and assigns as rosidl's setter does."""
    slot = "_" + name
    check = _checker(name, idl, class_of)
    special = s.special_typename(idl)
    keep_as_is: Callable[[Any], bool] | None = None  # numbers: rosidl's own containers
    if special is not None and isinstance(idl, d.Array):
        keep_as_is = _fixed_array_part("kept_as_is", name, special, idl.size)
        convert = _fixed_array_part("converter", special)
    elif special is not None:
        keep_as_is, convert = _array_store(name, special, idl), _sequence_converter(special)

    if keep_as_is is None:

        def set_value(self: Any, value: Any) -> None:
            if self._check_fields:
                check(value)
            setattr(self, slot, value)

    else:
        kept = keep_as_is

        def set_value(self: Any, value: Any) -> None:
            if self._check_fields:
                if kept(value):
                    setattr(self, slot, value)
                    return
                check(value)
            setattr(self, slot, convert(value))

    return property(attrgetter(slot), set_value, doc=f"Message field '{name}'.")


def _fixed_array_part(maker: str, *args: Any) -> Callable[..., Any]:
    """``_fixed_arrays.<maker>(*args)``, made when first called. Types with a fixed-size array
    are made that never hold a value (every service's ``Event`` type has a ``uint8[16]``), and
    importing numpy is what :mod:`._fixed_arrays` costs."""
    made: list[Callable[..., Any]] = []

    def call(*values: Any) -> Any:
        if not made:
            from launchkit.ros.msgs import _fixed_arrays

            made.append(getattr(_fixed_arrays, maker)(*args))
        return made[0](*values)

    return call


def _sequence_converter(special: str) -> Callable[[Any], Any]:
    code = s.TYPE_CODES[special]
    return lambda value: array.array(code, value)


def _array_store(name: str, special: str, idl: d.AbstractType) -> Callable[[Any], bool]:
    """With checks on: True for an ``array.array`` of the right type code (kept as it is)."""
    code = s.TYPE_CODES[special]
    bound = idl.maximum_size if isinstance(idl, d.BoundedSequence) else None

    def keep(value: Any) -> bool:
        if not isinstance(value, array.array):
            return False
        if value.typecode != code:
            raise AssertionError(f"The '{name}' array.array() must have the type code of '{code}'")
        if bound is not None and len(value) > bound:
            raise AssertionError(f"The '{name}' array.array() must have a size <= {bound}")
        return True

    return keep


def _checker(name: str, idl: d.AbstractType, class_of: ClassOf) -> Check:
    if isinstance(idl, d.AbstractNestedType):
        return _nested_checker(name, idl, class_of)
    if isinstance(idl, d.BoundedString):
        bound = idl.maximum_size
        message = f"The '{name}' field must be string value not longer than {bound}"
        return _assert(lambda v: isinstance(v, (str, UserString)) and len(v) <= bound, message)
    if isinstance(idl, d.NamespacedType):
        return _sub_message_checker(name, idl, class_of)
    if isinstance(idl, d.AbstractGenericString):
        return _assert(lambda v: isinstance(v, str), f"The '{name}' field must be of type 'str'")
    assert isinstance(idl, d.BasicType)
    if idl.typename == d.OCTET_TYPE:
        return _assert(
            lambda v: isinstance(v, (bytes, bytearray)) and len(v) == 1,
            f"The '{name}' field must be of type 'bytes' or 'ByteString' with length 1",
        )
    py_name = s.python_type_name(idl)
    py_type = _PY_TYPES[py_name]
    type_check = _assert(
        lambda v: isinstance(v, py_type), f"The '{name}' field must be of type '{py_name}'"
    )
    in_range = _scalar_range(name, idl.typename)
    if in_range is None:
        return type_check

    def check(value: Any) -> None:
        type_check(value)
        in_range(value)

    return check


def _sub_message_checker(name: str, idl: d.NamespacedType, class_of: ClassOf) -> Check:
    full = "/".join(idl.namespaced_name())
    message = f"The '{name}' field must be a sub message of type '{idl.name}'"

    def check(value: Any) -> None:
        if not isinstance(value, class_of(full)):
            raise AssertionError(message)

    return check


def _scalar_range(name: str, typename: str) -> Check | None:
    if typename in d.SIGNED_INTEGER_TYPES:
        bound = 2 ** (int(typename[3:]) - 1)
        low, high = -bound, bound
        message = f"The '{name}' field must be an integer in [{low}, {high - 1}]"
        return _assert(lambda v: low <= v < high, message)
    if typename in d.UNSIGNED_INTEGER_TYPES:
        high = 2 ** int(typename[4:])
        message = f"The '{name}' field must be an unsigned integer in [0, {high - 1}]"
        return _assert(lambda v: 0 <= v < high, message)
    if typename in FLOAT_BOUNDS:
        limit = FLOAT_BOUNDS[typename]
        message = f"The '{name}' field must be a {typename} in [{-limit!r}, {limit!r}]"
        return _assert(lambda v: not (v < -limit or v > limit) or math.isinf(v), message)
    return None


def _nested_checker(name: str, idl: d.AbstractNestedType, class_of: ClassOf) -> Check:
    """rosidl's one check of an array's or sequence's value, and its one message."""
    inner = idl.value_type
    suffixes = ["a set or sequence"]
    tests: list[Callable[[Any], bool]] = []
    if isinstance(inner, d.BoundedString):
        limit = inner.maximum_size
        suffixes.append(f"and each string value not longer than {limit}")
        tests.append(lambda v: all(len(x) <= limit for x in v))
    if isinstance(idl, d.BoundedSequence):
        maximum = idl.maximum_size
        suffixes.insert(1, f"with length <= {maximum}")
        tests.append(lambda v: len(v) <= maximum)
    elif isinstance(idl, d.Array):
        size = idl.size
        suffixes.insert(1, f"with length {size}")
        tests.append(lambda v: len(v) == size)
    py_name = s.python_type_name(inner)
    suffixes.append(f"and each value of type '{py_name}'")
    if isinstance(inner, d.NamespacedType):
        full = "/".join(inner.namespaced_name())
        tests.append(lambda v: all(isinstance(x, class_of(full)) for x in v))
    else:
        py_type = _PY_TYPES[py_name]
        tests.append(lambda v: all(isinstance(x, py_type) for x in v))
    if isinstance(inner, d.BasicType):
        each = _each_in_range(inner.typename)
        if each is not None:
            suffix, test = each
            suffixes.append(suffix)
            tests.append(test)
    message = f"The '{name}' field must be {' '.join(suffixes)}"

    def check(value: Any) -> None:
        if not (
            isinstance(value, (Sequence, Set, UserList))
            and not isinstance(value, (str, UserString))
            and all(test(value) for test in tests)
        ):
            raise AssertionError(message)

    return check


def _each_in_range(typename: str) -> tuple[str, Callable[[Any], bool]] | None:
    if typename in d.SIGNED_INTEGER_TYPES:
        bound = 2 ** (int(typename[3:]) - 1)
        return (
            f"and each integer in [{-bound}, {bound - 1}]",
            lambda v: all(-bound <= x < bound for x in v),
        )
    if typename in d.UNSIGNED_INTEGER_TYPES:
        high = 2 ** int(typename[4:])
        return (
            f"and each unsigned integer in [0, {high - 1}]",
            lambda v: all(0 <= x < high for x in v),
        )
    if typename in FLOAT_BOUNDS:
        limit = FLOAT_BOUNDS[typename]
        return (
            f"and each {typename} in [{-limit:f}, {limit:f}]",
            lambda v: all(not (x < -limit or x > limit) or math.isinf(x) for x in v),
        )
    return None


def _assert(test: Callable[[Any], bool], message: str) -> Check:
    def check(value: Any) -> None:
        if not test(value):
            raise AssertionError(message)

    return check


def default_factory(field: s.Field, idl: d.AbstractType, class_of: ClassOf) -> Callable[[], Any]:
    """What rosidl's constructor assigns to a field not given: the ``.msg`` default, else zero,
    empty or a default sub message (a new object on every call)."""
    if field.has_default:
        return default_value_factory(field, idl)
    if isinstance(idl, d.NamespacedType):
        full = "/".join(idl.namespaced_name())
        return lambda: class_of(full)()
    if isinstance(idl, d.Array):
        special = s.special_typename(idl)
        size = idl.size
        if special is not None:
            return _fixed_array_part("zeros", special, size)
        element = default_factory(s.Field(field.name, ("?", None)), idl.value_type, class_of)
        return lambda: [element() for _ in range(size)]
    if isinstance(idl, d.AbstractSequence):
        special = s.special_typename(idl)
        if special is not None:
            code = s.TYPE_CODES[special]
            return lambda: array.array(code)
        return list
    if isinstance(idl, d.AbstractGenericString):
        return str
    assert isinstance(idl, d.BasicType)
    if idl.typename == d.OCTET_TYPE:
        return lambda: b"\x00"
    return _PY_TYPES[s.python_type_name(idl)]


def default_value_factory(field: s.Field, idl: d.AbstractType) -> Callable[[], Any]:
    """The ``.msg`` default of ``field`` as rosidl's Python gives it (a new object per call)."""
    if not isinstance(idl, d.AbstractNestedType):
        value = python_value(idl, field.default)
        return lambda: value
    values = tuple(python_value(idl.value_type, v) for v in field.default)
    special = s.special_typename(idl)
    if special is not None and isinstance(idl, d.Array):
        return _fixed_array_part("of_values", special, values)
    if special is not None:
        code = s.TYPE_CODES[special]
        return lambda: array.array(code, values)
    return lambda: list(values)


def python_value(idl: d.AbstractType, value: Any) -> Any:
    """A ``.msg`` literal (default or constant) as rosidl's Python holds it."""
    if isinstance(idl, d.AbstractGenericString):
        return str(value)
    assert isinstance(idl, d.BasicType)
    if idl.typename == d.BOOLEAN_TYPE:
        return bool(value)
    if idl.typename == d.OCTET_TYPE:
        return bytes([value])
    if idl.typename in d.INTEGER_TYPES:
        return int(value)
    return float(value)
