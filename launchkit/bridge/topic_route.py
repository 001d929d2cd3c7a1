"""One bridged topic, one way: a subscription on the source side feeding a publisher on the
other, CDR bytes passed through untouched (``raw=True`` on both sides)."""

from __future__ import annotations

from typing import Any

from launchkit.bridge._rclpy import message_class, to_rclpy_qos
from launchkit.bridge.echo_guard import EchoGuard
from launchkit.bridge.plan import ZENOH, TopicRoute
from launchkit.ros.msgs import get_message
from launchkit.ros.node import Node

# the bridge's own DDS reader keeps this many samples while its executor catches up: Fast DDS
# does not announce writers' depths, and a burst must not overflow the bridge (KEEP_LAST drops)
READER_DEPTH = 1000


class MissingTypeError(LookupError):
    """A message type one of the two sides cannot create endpoints for."""


class TopicBridge:
    """Carries ``route.topic`` from ``route.source`` to the other side."""

    def __init__(
        self, route: TopicRoute, zenoh_node: Node, dds_node: Any, guard: EchoGuard, group: Any
    ) -> None:
        self.route = route
        self._zenoh_node = zenoh_node
        self._dds_node = dds_node
        self._guard = guard
        self._group = group
        self._closed = False
        self._source: Any = None
        self._dds_class = message_class(route.type_name)
        if self._dds_class is None:
            raise MissingTypeError(f"the rclpy install has no {route.type_name}")
        try:
            self._zenoh_class = get_message(route.type_name)
        except Exception:
            raise MissingTypeError(f"launchkit has no {route.type_name}") from None
        self._writes = guard.dds_writes(route.topic)
        if route.source == ZENOH:
            self._sink: Any = dds_node.create_publisher(
                self._dds_class, route.topic, to_rclpy_qos(route.qos)
            )
        else:
            self._sink = zenoh_node.create_publisher(self._zenoh_class, route.topic, route.qos)
            guard.zenoh_gids.add(self._sink.gid)
        if route.active:
            self.activate()

    @property
    def active(self) -> bool:
        """Whether the source side is subscribed."""
        return self._source is not None

    def activate(self) -> None:
        """Subscribe on the source side (messages start flowing)."""
        if self._source is not None:
            return
        if self.route.source == ZENOH:
            self._source = self._zenoh_node.create_subscription(
                self._zenoh_class, self.route.topic, self._from_zenoh, self.route.qos, raw=True
            )
        else:
            self._source = self._dds_node.create_subscription(
                self._dds_class,
                self.route.topic,
                self._from_dds,
                to_rclpy_qos(self.route.qos.replace(depth=max(self.route.qos.depth, READER_DEPTH))),
                raw=True,
                callback_group=self._group,
            )

    def deactivate(self) -> None:
        """Stop subscribing on the source side."""
        source, self._source = self._source, None
        if source is None:
            return
        if self.route.source == ZENOH:
            self._zenoh_node.destroy_subscription(source)
        else:
            self._dds_node.destroy_subscription(source)

    def _from_zenoh(self, data: bytes, info: dict[str, Any]) -> None:
        if self._closed or info["publisher_gid"] in self._guard.zenoh_gids:
            return  # a sample the bridge itself brought from DDS
        self._writes.write(data, self._sink.publish)

    def _from_dds(self, data: bytes, info: dict[str, Any]) -> None:
        # rclpy's executor takes one sample per wake-up (~100 us of Python each): take what
        # else is waiting here, so a burst costs one wake-up
        source = self._source
        while not self._closed:
            # Fast DDS hands over an empty sample when a writer goes away (no data, only the
            # news): CDR has at least its 4-byte header; and a sample the bridge wrote goes back
            if len(data) >= 4 and not self._writes.is_own(data, info):
                self._sink.publish(data)
            if source is None:
                return
            with source.handle:
                taken = source.handle.take_message(self._dds_class, True)
            if taken is None:
                return
            data, info = taken

    def close(self) -> None:
        """Undeclare both ends (the source first, so nothing arrives at a closed sink)."""
        self._closed = True
        self.deactivate()
        if self.route.source == ZENOH:
            self._dds_node.destroy_publisher(self._sink)
        else:
            self._guard.zenoh_gids.discard(self._sink.gid)
            self._zenoh_node.destroy_publisher(self._sink)
