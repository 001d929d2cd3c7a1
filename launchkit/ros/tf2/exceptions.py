"""tf2's exceptions, as ``tf2_py`` (and so ``tf2_ros``) exposes them, and the error codes a tree
walk returns before one is raised.

::

    TransformException
     ├── ConnectivityException      the two frames are in different trees
     ├── LookupException            a frame does not exist (or the tree has a loop)
     ├── ExtrapolationException     the time is outside the data (past, future, or no data)
     ├── InvalidArgumentException
     └── TimeoutException

Each carries tf2's message text as its one argument. Their module is ``tf2``, the name
``tf2_py`` gives them, so a traceback reads as it does under ROS 2.
"""

from __future__ import annotations

import enum


class TransformException(Exception):
    """The base of every tf2 error."""


class ConnectivityException(TransformException):
    """The frames are not part of the same tree."""


class LookupException(TransformException):
    """A frame does not exist, or the tree is invalid."""


class ExtrapolationException(TransformException):
    """The requested time is outside the data the buffer holds."""


class InvalidArgumentException(TransformException):
    """An argument is invalid (tf2 raises it for malformed requests)."""


class TimeoutException(TransformException):
    """A wait for a transform timed out (tf2's C++ API raises it; Python's lookups raise the
    underlying error instead)."""


for _exception in (
    TransformException,
    ConnectivityException,
    LookupException,
    ExtrapolationException,
    InvalidArgumentException,
    TimeoutException,
):
    _exception.__module__ = "tf2"


class TF2Error(enum.IntEnum):
    """tf2's error codes (``tf2::TF2Error``)."""

    NO_ERROR = 0
    LOOKUP_ERROR = 1
    CONNECTIVITY_ERROR = 2
    EXTRAPOLATION_ERROR = 3
    INVALID_ARGUMENT_ERROR = 4
    TIMEOUT_ERROR = 5
    TRANSFORM_ERROR = 6
    BACKWARD_EXTRAPOLATION_ERROR = 7
    FORWARD_EXTRAPOLATION_ERROR = 8
    NO_DATA_FOR_EXTRAPOLATION_ERROR = 9


_RAISED = {
    TF2Error.LOOKUP_ERROR: LookupException,
    TF2Error.CONNECTIVITY_ERROR: ConnectivityException,
    TF2Error.EXTRAPOLATION_ERROR: ExtrapolationException,
    TF2Error.INVALID_ARGUMENT_ERROR: InvalidArgumentException,
    TF2Error.TIMEOUT_ERROR: TimeoutException,
    TF2Error.TRANSFORM_ERROR: TransformException,
    # tf2's C++ subclasses of ExtrapolationException reach Python as ExtrapolationException
    TF2Error.BACKWARD_EXTRAPOLATION_ERROR: ExtrapolationException,
    TF2Error.FORWARD_EXTRAPOLATION_ERROR: ExtrapolationException,
    TF2Error.NO_DATA_FOR_EXTRAPOLATION_ERROR: ExtrapolationException,
}


def exception_for(code: TF2Error, message: str) -> TransformException:
    """The exception tf2 raises for ``code`` (not NO_ERROR), carrying ``message``."""
    return _RAISED[code](message)
