"""tf2_ros' ``BufferInterface``: ``transform()`` of any registered message type, and the
registries that make a type transformable (``TransformRegistration``) or convertible
(``ConvertRegistration``, ``convert``), as ``tf2_ros.buffer_interface`` has them.

A package such as ``tf2_geometry_msgs`` registers ``do_transform_*`` functions by message class
when it is imported; ``buffer.transform(msg, "map")`` then looks up the transform at the
message's stamp and applies the registered function.
"""

from __future__ import annotations

from collections.abc import Callable
from copy import deepcopy
from typing import Any, ClassVar

from launchkit.ros.clock import Duration
from launchkit.ros.msgs import get_message

Transformer = Callable[[Any, Any], Any]

#: tf2_ros' default timeout: do not wait
NO_WAIT = Duration()


class TypeException(Exception):
    """A type has no registered transform or conversion."""

    def __init__(self, errstr: str) -> None:
        super().__init__(errstr)
        self.errstr = errstr


class NotImplementedException(Exception):
    """A subclass of BufferInterface lacks ``can_transform`` or ``lookup_transform``."""

    def __init__(self) -> None:
        super().__init__()
        self.errstr = "CanTransform or LookupTransform not implemented"


class TransformRegistration:
    """The process-wide table of ``do_transform(obj, transform_stamped)`` by type."""

    _type_map: ClassVar[dict[Any, Transformer]] = {}

    def add(self, key: Any, callback: Transformer) -> None:
        """Transform objects of type ``key`` with ``callback``."""
        TransformRegistration._type_map[key] = callback

    def get(self, key: Any) -> Transformer:
        """The transform function of type ``key``; TypeException when there is none."""
        if key not in TransformRegistration._type_map:
            raise TypeException(f"Type {key} is not loaded or supported")
        return TransformRegistration._type_map[key]

    def print_me(self) -> None:
        """Print the table."""
        print(TransformRegistration._type_map)


class ConvertRegistration:
    """The process-wide tables of conversions to and from messages and between types."""

    _to_msg_map: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _from_msg_map: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _convert_map: ClassVar[dict[tuple[Any, Any], Callable[[Any], Any]]] = {}

    def add_from_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        """Make type ``key`` from a message with ``callback``."""
        ConvertRegistration._from_msg_map[key] = callback

    def add_to_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        """Make a message from type ``key`` with ``callback``."""
        ConvertRegistration._to_msg_map[key] = callback

    def add_convert(self, key: tuple[Any, Any], callback: Callable[[Any], Any]) -> None:
        """Convert between the pair of types ``key`` directly with ``callback``."""
        ConvertRegistration._convert_map[key] = callback

    def get_from_msg(self, key: Any) -> Callable[[Any], Any]:
        """The from-message conversion of ``key``; TypeException when there is none."""
        return _registered(ConvertRegistration._from_msg_map, key)

    def get_to_msg(self, key: Any) -> Callable[[Any], Any]:
        """The to-message conversion of ``key``; TypeException when there is none."""
        return _registered(ConvertRegistration._to_msg_map, key)

    def get_convert(self, key: tuple[Any, Any]) -> Callable[[Any], Any]:
        """The direct conversion for the pair ``key``; TypeException when there is none."""
        return _registered(ConvertRegistration._convert_map, key)


def _registered(table: dict[Any, Callable[[Any], Any]], key: Any) -> Callable[[Any], Any]:
    if key not in table:
        raise TypeException(f"Type {key} is not loaded or supported")
    return table[key]


def convert(a: Any, b_type: Any) -> Any:
    """``a`` as an object of type ``b_type``: a direct conversion if one is registered, a copy
    for the same type, else through its message form."""
    registry = ConvertRegistration()
    try:
        return registry.get_convert((type(a), b_type))(a)
    except TypeException:
        if type(a) is b_type:
            return deepcopy(a)
        return registry.get_from_msg(b_type)(registry.get_to_msg(type(a))(a))


def Stamped(obj: Any, stamp: Any, frame_id: str) -> Any:
    """Give ``obj`` a header with ``stamp`` and ``frame_id``."""
    obj.header = get_message("std_msgs/msg/Header")(frame_id=frame_id, stamp=stamp)
    return obj


class BufferInterface:
    """What a tf2 buffer offers: lookups (by subclasses) and ``transform`` built on them."""

    def __init__(self) -> None:
        self.registration = TransformRegistration()

    def transform(
        self,
        object_stamped: Any,
        target_frame: str,
        timeout: Duration = NO_WAIT,
        new_type: Any = None,
    ) -> Any:
        """``object_stamped`` (a registered stamped type) in ``target_frame``, looked up at its
        header's stamp, waiting up to ``timeout``; converted to ``new_type`` if given."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(
            object_stamped,
            self.lookup_transform(target_frame, header.frame_id, header.stamp, timeout),
        )
        return result if new_type is None else convert(result, new_type)

    def transform_full(
        self,
        object_stamped: Any,
        target_frame: str,
        target_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
        new_type: Any = None,
    ) -> Any:
        """As :meth:`transform`, into ``target_frame`` at ``target_time`` through
        ``fixed_frame`` (the advanced API)."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(
            object_stamped,
            self.lookup_transform_full(
                target_frame,
                target_time,
                header.frame_id,
                header.stamp,
                fixed_frame,
                timeout,
            ),
        )
        return result if new_type is None else convert(result, new_type)

    def lookup_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> Any:
        """The transform from ``source_frame`` to ``target_frame`` (a subclass provides it)."""
        raise NotImplementedException()

    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> Any:
        """The advanced lookup (a subclass provides it)."""
        raise NotImplementedException()

    def can_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Duration = NO_WAIT
    ) -> Any:
        """Whether the lookup would succeed (a subclass provides it)."""
        raise NotImplementedException()

    def can_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Duration = NO_WAIT,
    ) -> Any:
        """Whether the advanced lookup would succeed (a subclass provides it)."""
        raise NotImplementedException()
