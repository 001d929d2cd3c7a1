"""``tf2_py`` on launchkit: tf2's ``BufferCore`` and exceptions (:mod:`launchkit.ros.tf2`)."""

from launchkit.ros.tf2.buffer_core import BufferCore
from launchkit.ros.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)

__all__ = [
    "BufferCore",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
]
