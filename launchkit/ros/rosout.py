"""``/rosout``: what a node's logger prints, published as rcl_interfaces/msg/Log (rcl's rosout
handler, with its QoS: reliable, transient local, depth 1000)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launchkit.ros.logging import LoggingSeverity, add_rosout_sink, remove_rosout_sink
from launchkit.ros.msgs import get_message
from launchkit.ros.qos import QoSProfile, qos_profile_rosout_default

# a node's create_publisher
MakePublisher = Callable[[Any, str, QoSProfile], Any]

ROSOUT_TOPIC = "/rosout"
_NS = 1_000_000_000


class Rosout:
    """A node's ``/rosout`` publisher, fed by its logger and the logger's children."""

    def __init__(self, create_publisher: MakePublisher, logger_name: str) -> None:
        self._log_type = get_message("rcl_interfaces/msg/Log")
        self._time_type = get_message("builtin_interfaces/msg/Time")
        self._publisher: Any = create_publisher(
            self._log_type, ROSOUT_TOPIC, qos_profile_rosout_default
        )
        self._logger_name = logger_name
        add_rosout_sink(self._logger_name, self._publish)

    def _publish(
        self,
        level: LoggingSeverity,
        name: str,
        message: str,
        file: str,
        function: str,
        line: int,
        stamp_ns: int,
    ) -> None:
        sec, nanosec = divmod(stamp_ns, _NS)
        self._publisher.publish(
            self._log_type(
                stamp=self._time_type(sec=sec, nanosec=nanosec),
                level=int(level),
                name=name,
                msg=message,
                file=file,
                function=function,
                line=line,
            )
        )

    def destroy(self) -> None:
        """Stop publishing the logger's messages."""
        remove_rosout_sink(self._logger_name, self._publish)
