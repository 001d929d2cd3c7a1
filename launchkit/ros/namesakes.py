"""Two nodes of one name in one graph: each warns, once, when it sees the other.

Two nodes of one name share their parameter services and their logger name, and the tools reach
only one of them. ROS 2 warns about it in two places: rcl when one process holds two nodes of
one name (their ``/rosout`` publisher), and ``ros2 node list`` when it lists duplicates (as
``launchkit node list`` does). Across processes a ROS 2 node says nothing; a launchkit node
says so as soon as a namesake is in the graph, because the usual cause is a second
``launchkit run`` of the same file joining the graph of the first, and the first sign of it
would otherwise be a robot that behaves oddly.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import zenoh

from launchkit.ros.keyexpr import LIVELINESS_PREFIX, mangle, parse_token


class NamesakeWatch:
    """Follows the graph's nodes named like one node (a liveliness subscription on that name
    alone, the tokens already there included) and calls ``warn`` at the first other one."""

    def __init__(
        self,
        session: zenoh.Session,
        domain: int,
        own: tuple[str, str],
        namespace: str,
        name: str,
        warn: Callable[[str], object],
    ) -> None:
        ns = "" if namespace == "/" else namespace
        self._fqn = f"{ns}/{name}"
        self._domain = domain
        self._own = own  # (zid, node id) of this node's token
        self._warn = warn
        self._warned = threading.Event()
        self._subscriber: Any = session.liveliness().declare_subscriber(
            f"{LIVELINESS_PREFIX}/{domain}/*/*/*/NN/*/{mangle(ns)}/{name}",
            self._on_sample,
            history=True,
        )

    def _on_sample(self, sample: zenoh.Sample) -> None:
        token = parse_token(str(sample.key_expr))
        if sample.kind != zenoh.SampleKind.PUT or token is None:
            return
        if (token.zid, token.node_id) == self._own or self._warned.is_set():
            return
        self._warned.set()
        self._warn(
            f"another node named '{self._fqn}' is in the graph too (ROS_DOMAIN_ID "
            f"{self._domain}): the two share parameters and logs, and tools reach only one of "
            "them; is the same launch running twice? Rename one (--ros-args -r __node:=NAME, "
            "or a namespace)"
        )

    def destroy(self) -> None:
        """Stop following (the node is destroyed)."""
        try:
            self._subscriber.undeclare()
        except Exception:  # the session may be closed already
            pass
