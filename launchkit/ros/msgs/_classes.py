"""Message, service and action classes that behave as rosidl_generator_py's (Jazzy) do.

A message class has ``__slots__``, a keyword constructor with rosidl's defaults, a property per
field (:mod:`launchkit.ros.msgs._fields`), constants and ``NAME__DEFAULT`` values on the class
and, read-only, on its metaclass, rosidl's ``__repr__`` and ``__eq__``,
``get_fields_and_field_types()`` and ``SLOT_TYPES``. Its ``__module__`` is rosidl's
(``std_msgs.msg._string``), so ``repr()`` prints ``std_msgs.msg.String(data='')`` as rclpy does.
A service class holds ``Request``, ``Response`` and ``Event``; an action class ``Goal``, ``Result``,
``Feedback`` and ``Impl``. None has type support: launchkit encodes them itself (``_codec``).
"""

from __future__ import annotations

import array
import os
import re
from collections.abc import Callable
from copy import copy
from typing import Any, ClassVar

from launchkit.ros.msgs import _spec as s
from launchkit.ros.msgs import definition as d
from launchkit.ros.msgs._fields import (
    ClassOf,
    default_factory,
    default_value_factory,
    field_property,
    python_value,
)

#: rosidl reads this once, when a message module is imported; so does launchkit.
CHECK_FIELDS = os.environ.get("ROS_PYTHON_CHECK_FIELDS", "") == "1"

_ARRAY_PREFIX = "array('X', "


class MessageMeta(type):
    """The base of every message class's metaclass (``Metaclass_<Name>``, as rosidl names it):
    ``isinstance(cls, MessageMeta)`` tells a launchkit message class."""

    _TYPE_NAME: str
    _LK_FIELDS: tuple[tuple[str, Callable[[], Any], str | None], ...]
    _LK_NUMPY: frozenset[str]


class ServiceType:
    """A service type: ``Request``, ``Response`` and ``Event`` message classes, as rclpy's."""

    Request: ClassVar[Any]
    Response: ClassVar[Any]
    Event: ClassVar[Any]
    _TYPE_NAME: ClassVar[str]

    def __init__(self) -> None:
        raise NotImplementedError("Service classes can not be instantiated")


class ActionType:
    """An action type: ``Goal``, ``Result``, ``Feedback`` and ``Impl``, as rclpy's."""

    Goal: ClassVar[Any]
    Result: ClassVar[Any]
    Feedback: ClassVar[Any]
    Impl: ClassVar[Any]
    _TYPE_NAME: ClassVar[str]

    def __init__(self) -> None:
        raise NotImplementedError("Action classes can not be instantiated")


def module_name(type_name: str) -> str:
    """rosidl's module of a type: ``std_msgs/msg/String`` -> ``std_msgs.msg._string``,
    ``pkg/srv/AddTwoInts_Request`` -> ``pkg.srv._add_two_ints``."""
    pkg, kind, short = type_name.split("/")
    return f"{pkg}.{kind}._{snake_case(interface_stem(kind, short))}"


def interface_stem(kind: str, short: str) -> str:
    """The interface (file) name a type belongs to: ``AddTwoInts`` for ``AddTwoInts_Request``."""
    if kind == "msg":
        return short
    suffixes = s.SERVICE_SUFFIXES if kind == "srv" else s.ACTION_SUFFIXES
    for suffix in suffixes:
        if short.endswith(suffix) and len(short) > len(suffix):
            return short[: -len(suffix)]
    return short


def snake_case(name: str) -> str:
    """rosidl's ``convert_camel_case_to_lower_case_underscore``."""
    name = re.sub("(.)([A-Z][a-z]+)", r"\1_\2", name)
    return re.sub("([a-z0-9])([A-Z])", r"\1_\2", name).lower()


def message_class(spec: s.MessageSpec, class_of: ClassOf) -> MessageMeta:
    """The class of ``spec``; ``class_of(type_name)`` gives the classes of nested types."""
    short = spec.name.rsplit("/", 1)[1]
    fields = [f for f in spec.fields if f.name != d.EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME]
    idls = [s.idl_type(f.desc) for f in fields]
    constants = {
        c.name: python_value(s.idl_type((s.BASE, (c.base, 0))), c.value) for c in spec.constants
    }
    defaults = {
        f"{f.name.upper()}__DEFAULT": default_value_factory(f, idl)
        for f, idl in zip(fields, idls, strict=True)
        if f.has_default
    }
    meta = _metaclass(short, constants, defaults)
    namespace: dict[str, Any] = {
        "__slots__": [*("_" + f.name for f in fields), "_check_fields"],
        "__module__": module_name(spec.name),
        "__qualname__": short,
        "__doc__": _class_doc(short, list(constants)),
        "_fields_and_field_types": {
            f.name: s.field_type_string(idl) for f, idl in zip(fields, idls, strict=True)
        },
        "SLOT_TYPES": tuple(idls),
        "__init__": _init,
        "__repr__": _repr,
        "__eq__": _eq,
        "get_fields_and_field_types": classmethod(_get_fields_and_field_types),
        "_TYPE_NAME": spec.name,
        "_LK_FIELDS": tuple(
            _init_entry(f, idl, class_of) for f, idl in zip(fields, idls, strict=True)
        ),
        "_LK_NUMPY": frozenset(
            f.name
            for f, idl in zip(fields, idls, strict=True)
            if isinstance(idl, d.Array) and s.special_typename(idl)
        ),
        **constants,
        **{name: make() for name, make in defaults.items()},
    }
    for field, idl in zip(fields, idls, strict=True):
        namespace[field.name] = field_property(field.name, idl, class_of)
    cls = meta(short, (), namespace)
    assert isinstance(cls, MessageMeta)
    return cls


def _metaclass(
    short: str, constants: dict[str, Any], defaults: dict[str, Callable[[], Any]]
) -> type[MessageMeta]:
    """``Metaclass_<Name>``: the constants and ``NAME__DEFAULT`` values as read-only
    properties of the class (a default is a new object on every read, as rosidl's)."""
    namespace: dict[str, Any] = {"__doc__": f"Metaclass of message '{short}'."}
    for name, value in constants.items():
        namespace[name] = property(_returning(value), doc=f"Message constant '{name}'.")
    for name, make in defaults.items():
        field = name.removesuffix("__DEFAULT").lower()
        namespace[name] = property(
            _calling(make), doc=f"Return default value for message field '{field}'."
        )
    return type(f"Metaclass_{short}", (MessageMeta,), namespace)


def _returning(value: Any) -> Callable[[Any], Any]:
    return lambda cls: value


def _calling(make: Callable[[], Any]) -> Callable[[Any], Any]:
    return lambda cls: make()


def _class_doc(short: str, constants: list[str]) -> str:
    if not constants:
        return f"Message class '{short}'."
    names = "".join(f"      {name}\n" for name in constants)
    return f"\n    Message class '{short}'.\n\n    Constants:\n{names}    "


def _init_entry(
    field: s.Field, idl: d.AbstractType, class_of: ClassOf
) -> tuple[str, Callable[[], Any], str | None]:
    """How the constructor sets a field: name, default factory, and the ``array`` type code
    of a numeric sequence without a ``.msg`` default (rosidl converts those before the
    setter sees them)."""
    special = s.special_typename(idl)
    make = default_factory(field, idl, class_of)
    if special is None or field.has_default or not isinstance(idl, d.AbstractSequence):
        return (field.name, make, None)
    return (field.name, make, s.TYPE_CODES[special])


def _init(self: Any, **kwargs: Any) -> None:
    cls = type(self)
    check = kwargs["check_fields"] if "check_fields" in kwargs else CHECK_FIELDS
    self._check_fields = check
    if check:
        unknown = sorted(k for k in kwargs if "_" + k not in cls.__slots__)
        if unknown:
            raise AssertionError("Invalid arguments passed to constructor: " + ", ".join(unknown))
    for name, make_default, code in cls._LK_FIELDS:
        if name not in kwargs:
            setattr(self, name, make_default())
        elif code is not None:
            # rosidl converts here and again in the setter: without checks, once is the same
            value = kwargs[name]
            setattr(self, name, array.array(code, value) if check else value)
        else:
            setattr(self, name, kwargs[name])


def _repr(self: Any) -> str:
    cls = type(self)
    typename = cls.__module__.split(".")
    typename.pop()
    typename.append(cls.__name__)
    args = []
    for name, slot_type in zip(cls._fields_and_field_types, cls.SLOT_TYPES, strict=True):
        value = getattr(self, name)
        text = repr(value)
        if isinstance(slot_type, d.AbstractSequence) and s.special_typename(slot_type):
            if len(value) == 0:
                text = "[]"
            else:
                if self._check_fields:
                    assert text.startswith("array(")
                text = text[len(_ARRAY_PREFIX) : -1]
        args.append(f"{name}={text}")
    return f"{'.'.join(typename)}({', '.join(args)})"


def _eq(self: Any, other: Any) -> bool:
    if not isinstance(other, self.__class__):
        return False
    numpy_fields = type(self)._LK_NUMPY
    for name in type(self)._fields_and_field_types:
        if name in numpy_fields:
            if any(getattr(self, name) != getattr(other, name)):
                return False
        elif getattr(self, name) != getattr(other, name):
            return False
    return True


def _get_fields_and_field_types(cls: Any) -> dict[str, str]:
    """The field names and their types (a copy)."""
    return copy(cls._fields_and_field_types)


def service_class(
    type_name: str, request: type, response: type, event: type, base: type = ServiceType
) -> type[ServiceType]:
    """The class of service ``pkg/srv/Name`` (or an action's ``pkg/action/Name_SendGoal``)."""
    short = type_name.rsplit("/", 1)[1]
    meta = type(f"Metaclass_{short}", (type,), {"__doc__": f"Metaclass of service '{short}'."})
    cls = meta(
        short,
        (base,),
        {
            "__module__": module_name(type_name),
            "__qualname__": short,
            "__doc__": None,
            "Request": request,
            "Response": response,
            "Event": event,
            "_TYPE_NAME": type_name,
        },
    )
    assert isinstance(cls, type) and issubclass(cls, ServiceType)
    return cls


def action_class(type_name: str, parts: dict[str, Any]) -> type[ActionType]:
    """The class of action ``pkg/action/Name``; ``parts`` has Goal, Result, Feedback,
    SendGoalService, GetResultService, FeedbackMessage, CancelGoalService, GoalStatusMessage."""
    short = type_name.rsplit("/", 1)[1]
    impl_names = (
        "SendGoalService",
        "GetResultService",
        "FeedbackMessage",
        "CancelGoalService",
        "GoalStatusMessage",
    )
    impl = type(
        "Impl", (), {"__module__": module_name(type_name), **{n: parts[n] for n in impl_names}}
    )
    meta = type(f"Metaclass_{short}", (type,), {"__doc__": f"Metaclass of action '{short}'."})
    cls = meta(
        short,
        (ActionType,),
        {
            "__module__": module_name(type_name),
            "__qualname__": short,
            "__doc__": None,
            "Goal": parts["Goal"],
            "Result": parts["Result"],
            "Feedback": parts["Feedback"],
            "Impl": impl,
            "_TYPE_NAME": type_name,
        },
    )
    assert isinstance(cls, type) and issubclass(cls, ActionType)
    return cls
