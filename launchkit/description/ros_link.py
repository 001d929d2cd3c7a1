"""What launch actions ask of the launcher's own ROS node (launch_ros's ``ros_adapters``): load
components into a container, drive a lifecycle node, hear its transitions.

The description only knows this protocol; ``launchkit.ros_adapter`` implements it over
:mod:`launchkit.ros`, and the API hands it to the launch context. Replies arrive on the
adapter's threads and are posted back to the launch's loop (:meth:`LaunchContext.post`).
Without a link (``--print``) the actions say what they would do instead.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

#: ``report(level, logger, message)``: a launch line, printed on the launch's loop.
Report = Callable[[str, str, str], None]


@dataclass
class LoadRequest:
    """One ``composition_interfaces/srv/LoadNode`` request, evaluated."""

    package: str
    plugin: str
    node_name: str = ""
    namespace: str = ""
    remaps: list[str] = field(default_factory=list)
    #: (name, typed value) pairs and parameter files (whose section for the node the link
    #: reads), in order, global parameters first; later ones win
    parameters: list[tuple[str, Any] | Path] = field(default_factory=list)
    extra_arguments: list[tuple[str, Any]] = field(default_factory=list)


class RosLink(Protocol):
    """The launcher's ROS node, as actions use it."""

    def load_nodes(self, container: str, requests: list[LoadRequest], report: Report) -> None:
        """Load ``requests`` one after the other into ``container`` (its full name), once its
        ``~/_container/load_node`` service is there; report each result."""

    def watch_transitions(self, node: str, on_event: Callable[[Any], None]) -> None:
        """Call ``on_event(msg)`` (on the launch's loop) for each lifecycle_msgs
        TransitionEvent ``node`` publishes."""

    def change_state(self, node: str, transition_id: int, report: Report) -> None:
        """Ask ``node`` to make transition ``transition_id``; report a failure."""

    def close(self) -> None:
        """Stop waiting and calling, and leave the ROS graph."""
