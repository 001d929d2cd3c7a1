"""ROS 2 interface types the rosidl way: message, service and action classes, CDR, RIHS01 hashes.

Types come from the built-in store (rosbags' ROS 2 Jazzy messages, launchkit's services) and from
the ``msg/``, ``srv/`` and ``action/`` folders of packages the package index finds. Their classes
behave as rosidl's generated Python does. They are importable as
``from launchkit.ros.msgs.geometry_msgs.msg import Twist`` (always), as
``from geometry_msgs.msg import Twist`` once :func:`install` has put the import hook first on
``sys.meta_path`` (what the ``rclpy`` face's ``sitecustomize`` does), or by name with
:func:`get_message`, :func:`get_service` and :func:`get_action`.
"""

from __future__ import annotations

from launchkit.ros.msgs._api import (
    codec,
    deserialize,
    get_action,
    get_message,
    get_service,
    is_message,
    message_definition,
    message_spec,
    message_type_name,
    normalize_type_name,
    packages,
    register_types,
    serialize,
    type_hash,
    type_names,
)
from launchkit.ros.msgs._classes import ActionType, ServiceType
from launchkit.ros.msgs._importer import install, install_launchkit_prefix
from launchkit.ros.msgs._interface_files import InterfaceFileError
from launchkit.ros.msgs._registry import MessageTypeError

install_launchkit_prefix()

__all__ = [
    "ActionType",
    "InterfaceFileError",
    "MessageTypeError",
    "ServiceType",
    "codec",
    "deserialize",
    "get_action",
    "get_message",
    "get_service",
    "install",
    "is_message",
    "message_definition",
    "message_spec",
    "message_type_name",
    "normalize_type_name",
    "packages",
    "register_types",
    "serialize",
    "type_hash",
    "type_names",
]
