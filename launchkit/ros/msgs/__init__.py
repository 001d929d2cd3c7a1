"""ROS 2 Jazzy message and service types, CDR encoding and RIHS01 type hashes.

Types are importable the rclpy way, ``from launchkit.ros.msgs.geometry_msgs.msg import Twist``
(modules are made on import by ``_importer``), or by name with :func:`get_message` and
:func:`get_service`. Every message class has rclpy-style defaults: ``Twist()`` works.
"""

from __future__ import annotations

from launchkit.ros.msgs._api import (
    MessageTypeError,
    ServiceType,
    deserialize,
    get_message,
    get_service,
    message_definition,
    message_type_name,
    normalize_type_name,
    packages,
    serialize,
    type_hash,
    type_names,
)
from launchkit.ros.msgs._importer import install as _install_importer

_install_importer()

__all__ = [
    "MessageTypeError",
    "ServiceType",
    "deserialize",
    "get_message",
    "get_service",
    "message_definition",
    "message_type_name",
    "normalize_type_name",
    "packages",
    "serialize",
    "type_hash",
    "type_names",
]
