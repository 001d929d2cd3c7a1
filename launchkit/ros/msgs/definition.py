"""The field types of ROS 2 interfaces, as ``rosidl_parser.definition`` names them.

A message class's ``SLOT_TYPES`` holds one of these per field, as rosidl's generated Python does,
so code that inspects messages the rosidl way (``isinstance(t, AbstractSequence)``,
``t.value_type.typename``) works on launchkit's classes. Only what a ``.msg`` file can express
is here: the IDL-only kinds (``char``, ``wchar``, ``long double``) never come out of a ``.msg``.
"""

from __future__ import annotations

from collections.abc import Iterable

#: IDL names of the basic types a ``.msg`` file produces (``float32`` is ``float``, ``bool`` is
#: ``boolean``, ``byte`` is ``octet``, and ``char`` is ``uint8``, as rosidl_adapter maps them).
FLOATING_POINT_TYPES = ("float", "double")
SIGNED_INTEGER_TYPES = ("int8", "int16", "int32", "int64")
UNSIGNED_INTEGER_TYPES = ("uint8", "uint16", "uint32", "uint64")
INTEGER_TYPES = (*SIGNED_INTEGER_TYPES, *UNSIGNED_INTEGER_TYPES)
BOOLEAN_TYPE = "boolean"
OCTET_TYPE = "octet"
EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME = "structure_needs_at_least_one_member"


class AbstractType:
    """Any field type; two are equal when they are of the same kind with the same details."""

    __slots__ = ()

    def _key(self) -> tuple[object, ...]:
        return ()

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, AbstractType)
            and type(other) is type(self)
            and self._key() == other._key()
        )

    def __hash__(self) -> int:
        return hash((type(self).__name__, self._key()))

    def __repr__(self) -> str:
        return f"{type(self).__name__}{self._key()!r}"


class AbstractNestableType(AbstractType):
    """A type that can be the element of an array or sequence."""

    __slots__ = ()


class BasicType(AbstractNestableType):
    """A number, ``boolean`` or ``octet``."""

    __slots__ = ("typename",)

    def __init__(self, typename: str) -> None:
        self.typename = typename

    def _key(self) -> tuple[object, ...]:
        return (self.typename,)


class NamespacedType(AbstractNestableType):
    """Another message type: ``NamespacedType(['std_msgs', 'msg'], 'Header')``."""

    __slots__ = ("name", "namespaces")

    def __init__(self, namespaces: Iterable[str], name: str) -> None:
        self.namespaces = list(namespaces)
        self.name = name

    def namespaced_name(self) -> tuple[str, ...]:
        """``('std_msgs', 'msg', 'Header')``."""
        return (*self.namespaces, self.name)

    def _key(self) -> tuple[object, ...]:
        return (tuple(self.namespaces), self.name)


class AbstractGenericString(AbstractNestableType):
    """A string, bounded or not."""

    __slots__ = ()

    def has_maximum_size(self) -> bool:
        """Whether the string has an upper bound."""
        return False


class AbstractString(AbstractGenericString):
    """A UTF-8 string."""

    __slots__ = ()


class UnboundedString(AbstractString):
    """``string``."""

    __slots__ = ()


class BoundedString(AbstractString):
    """``string<=N``."""

    __slots__ = ("maximum_size",)

    def __init__(self, maximum_size: int) -> None:
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        """Always: the bound is ``maximum_size``."""
        return True

    def _key(self) -> tuple[object, ...]:
        return (self.maximum_size,)


class AbstractNestedType(AbstractType):
    """An array or sequence of ``value_type``."""

    __slots__ = ("value_type",)

    def __init__(self, value_type: AbstractNestableType) -> None:
        self.value_type = value_type

    def has_maximum_size(self) -> bool:
        """Whether the number of elements has an upper bound."""
        return False

    def _key(self) -> tuple[object, ...]:
        return (self.value_type,)


class Array(AbstractNestedType):
    """``T[N]``: exactly ``size`` elements."""

    __slots__ = ("size",)

    def __init__(self, value_type: AbstractNestableType, size: int) -> None:
        super().__init__(value_type)
        self.size = size

    def has_maximum_size(self) -> bool:
        """Always: ``size``."""
        return True

    def _key(self) -> tuple[object, ...]:
        return (self.value_type, self.size)


class AbstractSequence(AbstractNestedType):
    """A sequence of any length (bounded or not)."""

    __slots__ = ()


class UnboundedSequence(AbstractSequence):
    """``T[]``."""

    __slots__ = ()


class BoundedSequence(AbstractSequence):
    """``T[<=N]``."""

    __slots__ = ("maximum_size",)

    def __init__(self, value_type: AbstractNestableType, maximum_size: int) -> None:
        super().__init__(value_type)
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        """Always: ``maximum_size``."""
        return True

    def _key(self) -> tuple[object, ...]:
        return (self.value_type, self.maximum_size)
