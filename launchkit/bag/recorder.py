"""``launchkit bag record``'s core: discover topics, subscribe raw, hand messages to the writer.

Messages are never decoded: a raw subscription delivers the CDR bytes and rmw's message info
(receive time, the publisher's GID and sequence number). Each topic is subscribed with a QoS
adapted to what its publishers offer (read from their liveliness tokens), and those offers go
into the bag. New topics are picked up while recording: the graph wakes the recorder, which
also looks every ``polling_interval`` as rosbag2 does.
"""

from __future__ import annotations

import threading
from collections import defaultdict
from dataclasses import dataclass

from launchkit.bag.metadata import TopicRecord
from launchkit.bag.qos import request_for_offers, to_bag_qos
from launchkit.bag.selection import TopicSelection
from launchkit.bag.storage import BagTopic
from launchkit.bag.writer_thread import WriterThread
from launchkit.ros.keyexpr import Token
from launchkit.ros.msgs import MessageTypeError, get_message, message_definition, type_hash
from launchkit.ros.node import Node
from launchkit.ros.params import Parameter
from launchkit.ros.topics import MessageInfo, Subscription


@dataclass(frozen=True)
class RecorderOptions:
    """What to record and how to find it (rosbag2's recorder options of the same names)."""

    selection: TopicSelection
    polling_interval: float = 0.1
    no_discovery: bool = False
    use_sim_time: bool = False


class SequenceGaps:
    """Messages a publisher sent that never arrived, from its sequence numbers."""

    def __init__(self) -> None:
        self._last: dict[bytes, int] = {}
        self.missed: dict[str, int] = defaultdict(int)

    def add(self, topic: str, gid: bytes, sequence: int) -> None:
        """Note that ``sequence`` of publisher ``gid`` arrived on ``topic``."""
        if not gid or sequence <= 0:
            return
        last = self._last.get(gid)
        if last is not None and sequence > last + 1:
            self.missed[topic] += sequence - last - 1
        if last is None or sequence > last:
            self._last[gid] = sequence


class Recorder:
    """Subscribes to the selected topics of the graph and queues their messages for the bag."""

    def __init__(self, node: Node, writer: WriterThread, options: RecorderOptions) -> None:
        self.node = node
        self.writer = writer
        self.options = options
        self.received: dict[str, int] = defaultdict(int)
        self.gaps = SequenceGaps()
        self.subscriptions: dict[str, Subscription] = {}
        self._skipped: set[tuple[str, str]] = set()
        self._changed = threading.Event()
        self._discovering = not options.no_discovery
        self._log = node.get_logger()
        if options.use_sim_time:
            node.set_parameters([Parameter("use_sim_time", value=True)])
        self._changed.set()
        node.context.graph.add_listener(self._on_graph)

    def _on_graph(self, token: Token, appeared: bool) -> None:
        # zenoh's thread: only note it and wake the spinning thread, which discovers
        if appeared and token.kind == "MP" and token.topic not in self.subscriptions:
            self._changed.set()
            self.node.wake()

    @property
    def discovering(self) -> bool:
        """False once discovery has stopped (``--no-discovery``, or every named topic found)."""
        return self._discovering

    def discovery_due(self) -> bool:
        """Whether the graph changed since the last look."""
        return self._changed.is_set()

    def discover(self) -> None:
        """Subscribe to every selected topic that has publishers and is not recorded yet."""
        self._changed.clear()
        publishers: dict[str, list[Token]] = defaultdict(list)
        for token in self.node.context.graph.tokens("MP"):
            publishers[token.topic].append(token)
        for topic in sorted(publishers):
            if topic not in self.subscriptions and self.options.selection.wants(topic):
                self._subscribe(topic, publishers[topic])
        selection = self.options.selection
        if (
            self._discovering
            and not (selection.all or selection.regex)
            and selection.topics <= set(self.subscriptions)
        ):
            self._log.info("All requested topics are subscribed. Stopping discovery...")
            self._discovering = False

    def _skip(self, topic: str, type_name: str, why: str) -> None:
        if (topic, type_name) not in self._skipped:
            self._skipped.add((topic, type_name))
            self._log.warn(f"Not recording topic '{topic}' of type '{type_name}': {why}")

    def _subscribe(self, topic: str, tokens: list[Token]) -> None:
        type_name = tokens[0].type_name
        same_type = [t for t in tokens if t.type_name == type_name]
        for other in {t.type_name for t in tokens} - {type_name}:
            self._skip(topic, other, f"the topic is recorded as '{type_name}'")
        try:
            msg_type = get_message(type_name)
        except MessageTypeError:
            self._skip(topic, type_name, "the type is not a ROS 2 Jazzy type launchkit knows")
            return
        expected_hash = type_hash(type_name)
        if any(t.type_hash != expected_hash for t in same_type):
            self._skip(
                topic, type_name, f"its publishers' type hash is not Jazzy's ({expected_hash})"
            )
            return
        offers = [t.qos for t in same_type if t.qos is not None]
        record = TopicRecord(
            name=topic,
            type=type_name,
            type_hash=expected_hash,
            qos=[to_bag_qos(q) for q in offers],
        )
        bag_topic = self.writer.declare(record, message_definition(type_name))
        qos = request_for_offers(topic, offers, self._log.warn)

        def on_message(data: bytes, info: MessageInfo) -> None:
            self._on_message(bag_topic, data, info)

        self.subscriptions[topic] = self.node.create_subscription(
            msg_type, topic, on_message, qos, raw=True
        )
        self._log.info(f"Subscribed to topic '{topic}'")

    def _on_message(self, topic: BagTopic, data: bytes, info: MessageInfo) -> None:
        name = topic.record.name
        self.received[name] += 1
        self.gaps.add(name, info["publisher_gid"], info["publication_sequence_number"])
        if self.options.use_sim_time:
            timestamp = self.node.get_clock().now().nanoseconds
            if timestamp == 0:  # no /clock yet: rosbag2 writes nothing until the first one
                return
        else:
            timestamp = info["received_timestamp"]
        self.writer.put(topic, timestamp, data)

    def stop(self) -> None:
        """Unsubscribe from everything (no message is delivered after this)."""
        self.node.context.graph.remove_listener(self._on_graph)
        for subscription in self.subscriptions.values():
            self.node.destroy_subscription(subscription)

    def report(self) -> list[str]:
        """What was recorded and what was lost, one line per fact (for the log)."""
        dropped = dict(self.writer.dropped)
        missed = {t: n for t, n in self.gaps.missed.items() if n}
        received = sum(self.received.values())
        lines = [
            f"Received {received} messages on {len(self.subscriptions)} topics; "
            f"{sum(dropped.values())} dropped (writer queue full), "
            f"{sum(missed.values())} missed (gaps in publishers' sequence numbers)"
        ]
        for topic in sorted(set(dropped) | set(missed)):
            lines.append(
                f"  {topic}: {dropped.get(topic, 0)} dropped, {missed.get(topic, 0)} missed"
            )
        return lines
