"""``serialize_message`` and ``deserialize_message`` (rclpy's ``rclpy.serialization``): a
message to CDR bytes (with their 4-byte header) and back."""

from __future__ import annotations

from typing import Any

from launchkit.ros.msgs import deserialize, message_type_name, serialize


def serialize_message(message: Any) -> bytes:
    """The CDR bytes of ``message``."""
    return serialize(message, message_type_name(message))


def deserialize_message(serialized_message: bytes, message_type: Any) -> Any:
    """A ``message_type`` message from its CDR bytes."""
    return deserialize(serialized_message, message_type_name(message_type))
