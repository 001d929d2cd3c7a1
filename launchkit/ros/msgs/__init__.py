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

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes
from launchkit.ros.msgs._importer import install, install_launchkit_prefix

if TYPE_CHECKING:
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
    from launchkit.ros.msgs._interface_files import InterfaceFileError
    from launchkit.ros.msgs._registry import MessageTypeError

# Names are imported on first use (PEP 562): the import hook is installed when a process starts
# (the rclpy face's sitecustomize), and must not load rosbags and the classes then.
_LAZY = {
    "codec": "._api",
    "deserialize": "._api",
    "get_action": "._api",
    "get_message": "._api",
    "get_service": "._api",
    "is_message": "._api",
    "message_definition": "._api",
    "message_spec": "._api",
    "message_type_name": "._api",
    "normalize_type_name": "._api",
    "packages": "._api",
    "register_types": "._api",
    "serialize": "._api",
    "type_hash": "._api",
    "type_names": "._api",
    "ActionType": "._classes",
    "ServiceType": "._classes",
    "InterfaceFileError": "._interface_files",
    "MessageTypeError": "._registry",
}

__getattr__ = lazy_attributes(__name__, _LAZY, globals())

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
