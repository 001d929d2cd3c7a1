"""Small value classes without :mod:`dataclasses`, for the modules every launch imports.

Importing :mod:`dataclasses` imports :mod:`inspect` (and with it ``ast``, ``dis``,
``tokenize``), and each ``@dataclass`` compiles its methods with ``exec`` when its module is
imported: together a fifth of ``launchkit run``'s own start-up on a busy machine (see
docs/benchmarks.md, issue 15). A class that derives from :class:`Record` declares its fields
as annotations, lists them in ``__slots__`` too, and writes its own ``__init__``; equality and
``repr`` (and for :class:`Frozen`, hashing and immutability) come from here and behave as a
dataclass's do: fields in the order they are declared, compared only with an instance of the
very same class.

A record class does not derive from another record class (its fields are its own).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar


class Record:
    """A class whose fields are its annotations (and its ``__slots__``): compared, and shown,
    field by field."""

    __slots__ = ()
    #: The fields, in the order they are declared.
    field_names: ClassVar[tuple[str, ...]] = ()

    def __init_subclass__(cls) -> None:
        super().__init_subclass__()
        # not inspect.get_annotations: inspect is what this module exists to avoid importing
        cls.field_names = tuple(cls.__dict__.get("__annotations__", ()))  # noqa: RUF063
        if set(cls.field_names) != set(cls.__dict__.get("__slots__", ("?",))):
            raise TypeError(f"{cls.__name__}: the annotations and __slots__ name other fields")

    def fields(self) -> tuple[Any, ...]:
        """The fields' values, in the order they are declared."""
        return tuple(getattr(self, name) for name in self.field_names)

    def __eq__(self, other: object) -> bool:
        if other.__class__ is self.__class__:
            assert isinstance(other, Record)
            return self.fields() == other.fields()
        return NotImplemented

    __hash__: ClassVar[None]  # type: ignore[assignment]  # mutable: unhashable, as a dataclass

    def __repr__(self) -> str:
        shown = ", ".join(f"{name}={getattr(self, name)!r}" for name in self.field_names)
        return f"{type(self).__qualname__}({shown})"


class Frozen(Record):
    """A :class:`Record` whose fields cannot change after ``__init__`` (which sets them with
    ``object.__setattr__``); hashable."""

    __slots__ = ()

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field {name!r} of a frozen {type(self).__name__}")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field {name!r} of a frozen {type(self).__name__}")

    def __hash__(self) -> int:  # type: ignore[override]
        return hash(self.fields())

    def __reduce__(self) -> tuple[Any, ...]:
        # copy, deepcopy and pickle: the default sets the slots with setattr, refused here
        return _rebuild, (type(self), self.fields())


def slot_setters(cls: type[Frozen]) -> tuple[Callable[[Any, Any], None], ...]:
    """The setters of ``cls``'s slots, one per field in declaration order: a frozen record made
    once per element of a large file sets its fields with these in ``__init__`` (half what
    ``object.__setattr__`` by name costs)."""
    return tuple(cls.__dict__[name].__set__ for name in cls.field_names)


def _rebuild(cls: type[Frozen], values: tuple[Any, ...]) -> Frozen:
    record = object.__new__(cls)
    for name, value in zip(cls.field_names, values, strict=True):
        object.__setattr__(record, name, value)
    return record
