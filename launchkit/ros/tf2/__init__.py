"""tf2 for Python on launchkit's ROS layer: what ``tf2_py``, ``tf2_ros`` and
``tf2_geometry_msgs`` offer in ROS 2 Jazzy.

::

    from launchkit.ros.tf2 import Buffer, TransformListener

    buffer = Buffer()
    listener = TransformListener(buffer, node)
    t = buffer.lookup_transform("odom", "base", Time(), timeout=Duration(seconds=1))

``buffer_core`` is tf2's buffer (per-frame history, interpolation, chaining through the tree,
tf2's exceptions and messages); ``buffer``, ``transform_listener``, the two broadcasters and
``buffer_interface`` are tf2_ros; ``tf2_geometry_msgs`` transforms geometry messages (import it
to register them with ``Buffer.transform``). The ``tf2_ros`` face package re-exports them under
their ROS names.
"""

from __future__ import annotations

from launchkit.ros.tf2.buffer import Buffer
from launchkit.ros.tf2.buffer_core import BufferCore
from launchkit.ros.tf2.buffer_interface import (
    BufferInterface,
    ConvertRegistration,
    NotImplementedException,
    Stamped,
    TransformRegistration,
    TypeException,
    convert,
)
from launchkit.ros.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from launchkit.ros.tf2.static_transform_broadcaster import StaticTransformBroadcaster
from launchkit.ros.tf2.transform_broadcaster import TransformBroadcaster
from launchkit.ros.tf2.transform_listener import TransformListener

__all__ = [
    "Buffer",
    "BufferCore",
    "BufferInterface",
    "ConnectivityException",
    "ConvertRegistration",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "NotImplementedException",
    "Stamped",
    "StaticTransformBroadcaster",
    "TimeoutException",
    "TransformBroadcaster",
    "TransformException",
    "TransformListener",
    "TransformRegistration",
    "TypeException",
    "convert",
]
