"""``rclpy.serialization``: messages to CDR bytes and back."""

from launchkit.ros.serialization import deserialize_message, serialize_message

__all__ = ["deserialize_message", "serialize_message"]
