"""Publishers and subscriptions over Zenoh, with rmw_zenoh keys, attachments and tokens."""

from __future__ import annotations

import inspect
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypedDict

import zenoh
from zenoh import ext

from launchkit.ros.event_handler import MatchedEvent
from launchkit.ros.keyexpr import decode_attachment, encode_attachment, entity_token, gid_of
from launchkit.ros.lockstep.participant import stamp_ns
from launchkit.ros.msgs import codec, message_type_name, type_hash
from launchkit.ros.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from launchkit.ros.task import await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.node_interface import NodeInterface


class MessageInfo(TypedDict):
    """What a two-argument subscription callback gets besides the message (rclpy's keys).

    Timestamps are nanoseconds since the epoch: ``source_timestamp`` when the publisher sent it
    (from rmw_zenoh's attachment; 0 if none), ``received_timestamp`` when this process's Zenoh
    session got it. ``publisher_gid`` (rmw's ``publisher_gid``, not in rclpy's dict) tells
    whose ``publication_sequence_number`` it is.
    """

    source_timestamp: int
    received_timestamp: int
    publication_sequence_number: int
    reception_sequence_number: int
    publisher_gid: bytes


def _wants_message_info(callback: Callable[..., Any]) -> bool:
    """Whether ``callback`` takes ``(msg, message_info)`` rather than ``(msg)`` (rclpy's test)."""
    try:
        signature = inspect.signature(callback)
    except (TypeError, ValueError):  # a builtin without a signature: the one-argument form
        return False
    try:
        signature.bind(object())
        return False
    except TypeError:
        pass
    try:
        signature.bind(object(), object())
        return True
    except TypeError:
        return False


class _Entity:
    """What publishers and subscriptions share: names, key, liveliness token, GID."""

    KIND = ""

    def __init__(
        self,
        node: NodeInterface,
        msg_type: Any,
        topic: str,
        qos: QoSProfile,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        self.node = node
        self.msg_type = msg_type
        self.type_name = message_type_name(msg_type)
        self.topic_name = node.resolve_topic_name(topic)
        self.qos_profile = qos
        # before anything can arrive: the executor asks the group of every ready entity
        self.callback_group = callback_group or node.default_callback_group
        self.callback_group.add_entity(self)
        self.event_handlers: list[MatchedEvent] = []
        qos = qos.resolved()  # what goes on the wire: rmw_zenoh's defaults for the rest
        self.type_hash = type_hash(self.type_name)
        self.key = node.topic_key(self.topic_name, self.type_name, self.type_hash)
        self.entity_id = node.context.next_entity_id()
        self.token_key = entity_token(
            node.context.domain_id,
            node.zid,
            node.node_id,
            self.entity_id,
            self.KIND,
            node.context.ros_args.enclave,
            node.get_namespace(),
            node.get_name(),
            self.topic_name,
            self.type_name,
            self.type_hash,
            qos,
        )
        self.gid = gid_of(self.token_key)
        self._codec = codec(self.type_name)
        self._token: Any = None

    def _announce(self) -> None:
        self._token = self.node.context.session.liveliness().declare_token(self.token_key)
        # follow the graph from the first publisher or subscription on, so that graph queries
        # soon after (get_node_names, get_subscription_count) find it already filled; not in a
        # command's client session (every node has a /parameter_events publisher), where it
        # would answer the command's own one-off graph queries only in part
        if not self.node.context.client:
            _ = self.node.context.graph

    def _set_event_callbacks(self, callbacks: Any) -> None:
        """Start the event handlers ``callbacks`` asks for (the matched event)."""
        matched = getattr(callbacks, "matched", None)
        if matched is not None:
            peer = "MS" if self.KIND == "MP" else "MP"
            self.event_handlers.append(MatchedEvent(self, matched, peer, self.node.post))

    def _undeclare(self, *entities: Any) -> None:
        for handler in self.event_handlers:
            handler.destroy()
        self.event_handlers.clear()
        for entity in (*entities, self._token):
            if entity is None:
                continue
            try:
                entity.undeclare()
            except Exception:  # the session may be closed already
                pass
        self._token = None


class Publisher(_Entity):
    """Publishes messages of one type on one topic (``publish``, ``get_subscription_count``)."""

    KIND = "MP"

    def __init__(
        self,
        node: NodeInterface,
        msg_type: Any,
        topic: str,
        qos: QoSProfile,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, msg_type, topic, qos, callback_group)
        qos = qos.resolved()
        session = node.context.session
        self._sequence = 0
        self._lock = threading.Lock()
        reliable = qos.reliability == ReliabilityPolicy.RELIABLE
        congestion = (
            zenoh.CongestionControl.BLOCK
            if reliable and qos.history == HistoryPolicy.KEEP_ALL
            else zenoh.CongestionControl.DROP
        )
        if qos.durability == DurabilityPolicy.TRANSIENT_LOCAL:
            self._pub: Any = ext.declare_advanced_publisher(
                session,
                self.key,
                cache=ext.CacheConfig(max_samples=qos.effective_depth),
                publisher_detection=True,
                sample_miss_detection=(
                    ext.MissDetectionConfig(heartbeat=None, sporadic_heartbeat=0.5)
                    if reliable
                    else None
                ),
                congestion_control=congestion,
                reliability=zenoh.Reliability.RELIABLE
                if reliable
                else zenoh.Reliability.BEST_EFFORT,
            )
        else:
            self._pub = session.declare_publisher(
                self.key,
                congestion_control=congestion,
                reliability=zenoh.Reliability.RELIABLE
                if reliable
                else zenoh.Reliability.BEST_EFFORT,
            )
        self._announce()

    @property
    def topic(self) -> str:
        """The resolved topic name."""
        return self.topic_name

    def publish(self, msg: Any) -> None:
        """Serialize ``msg`` (CDR) and send it with rmw_zenoh's attachment."""
        data: bytes | bytearray
        if getattr(msg, "_TYPE_NAME", None) == self.type_name:
            data = self._codec.serialize(msg)  # a bytearray: Zenoh copies it once, as bytes
        elif isinstance(msg, (bytes, bytearray)):
            data = msg
        elif isinstance(msg, memoryview):
            data = bytes(msg)  # Zenoh takes bytes or bytearray only
        else:
            raise TypeError(
                f"publisher on '{self.topic_name}' expects {self.type_name}, "
                f"got {type(msg).__name__}"
            )
        if self.node.context.refused is not None:
            return  # linked to another user's router: nothing more leaves (context.py)
        with self._lock:
            self._sequence += 1
            stamp = stamp_ns(self.node.context)
            attachment = encode_attachment(self._sequence, stamp, self.gid)
            self._pub.put(data, attachment=attachment)

    def get_subscription_count(self) -> int:
        """How many matching subscriptions (of any process) exist now."""
        return len(
            [
                t
                for t in self.node.context.graph.tokens("MS", self.topic_name)
                if t.type_name == self.type_name
            ]
        )

    def wait_for_subscriptions(self, count: int = 1, timeout_sec: float | None = None) -> bool:
        """Block until at least ``count`` subscriptions match (launchkit extension)."""
        return self.node.context.graph.wait_for(
            lambda: self.get_subscription_count() >= count, timeout_sec
        )

    def destroy(self) -> None:
        """Undeclare the publisher and its token."""
        self._undeclare(self._pub)
        self.node.forget(self)


class Subscription(_Entity):
    """Calls ``callback(msg)`` in the spinning thread for every message on a topic.

    As in rclpy, a callback taking two arguments gets ``(msg, message_info)``
    (:class:`MessageInfo`); with ``raw=True`` the message is its CDR ``bytes``, never decoded.

    As rmw_zenoh's, the subscription keeps its own queue of received messages: at most
    ``depth`` of them for KEEP_LAST (the oldest is dropped for a new one: a slow callback sees
    the latest messages, and memory stays bounded whatever the publishers send), all of them
    for KEEP_ALL. The node's work queue holds at most one "take the next message" item per
    subscription, so other callbacks get their turn between two messages.
    """

    KIND = "MS"

    def __init__(
        self,
        node: NodeInterface,
        msg_type: Any,
        topic: str,
        callback: Callable[..., Any],
        qos: QoSProfile,
        raw: bool = False,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, msg_type, topic, qos, callback_group)
        qos = qos.resolved()
        self.callback = callback
        self.raw = raw
        self._with_info = _wants_message_info(callback)
        self._received = 0
        self._queue: deque[tuple[bytes, bytes | None, int]] = deque()
        self._queue_lock = threading.Lock()
        self._depth = None if qos.history == HistoryPolicy.KEEP_ALL else qos.effective_depth
        self._scheduled = False  # the subscription waits in the node's work queue
        self._executor_event = False  # an executor's handler for it is pending
        self.on_arrival: Callable[[], None] | None = None  # told of every message (any thread)
        self.dropped = 0  # messages pushed out of a full queue (launchkit extension)
        session = node.context.session
        reliable = qos.reliability == ReliabilityPolicy.RELIABLE
        if qos.durability == DurabilityPolicy.TRANSIENT_LOCAL:
            self._sub: Any = ext.declare_advanced_subscriber(
                session,
                self.key,
                self._on_sample,
                history=ext.HistoryConfig(
                    detect_late_publishers=True, max_samples=qos.effective_depth
                ),
                recovery=(
                    ext.RecoveryConfig(periodic_queries=None, heartbeat=True) if reliable else None
                ),
                subscriber_detection=True,
            )
        else:
            self._sub = session.declare_subscriber(self.key, self._on_sample)
        self._announce()

    @property
    def topic(self) -> str:
        """The resolved topic name."""
        return self.topic_name

    def _on_sample(self, sample: zenoh.Sample) -> None:
        # zenoh's thread: copy out, queue, and have the spinning thread take it; the
        # attachment and reception time only matter to a callback that takes message_info
        if self.node.context.refused is not None:
            return  # from another user's router
        item: tuple[bytes, bytes | None, int]
        lockstep = self.node.context.lockstep
        if self._with_info or lockstep is not None:
            attachment = sample.attachment
            item = (
                sample.payload.to_bytes(),
                None if attachment is None else attachment.to_bytes(),
                time.time_ns(),
            )
        else:
            item = (sample.payload.to_bytes(), None, 0)
        if lockstep is not None:
            lockstep.received(item[1])
        with self._queue_lock:
            if self._depth is not None and len(self._queue) >= self._depth:
                dropped = self._queue.popleft()
                self.dropped += 1
                if lockstep is not None:
                    lockstep.handled(self, dropped[1])
            self._queue.append(item)
            scheduled, self._scheduled = self._scheduled, True
        if self.on_arrival is not None:
            self.on_arrival()
        if not scheduled:
            self.node.post(self)

    def take_message(self) -> tuple[Any, ...] | None:
        """The callback's arguments for the oldest queued message (None: none waits)."""
        with self._queue_lock:
            if not self._queue:
                self._scheduled = False
                return None
            item = self._queue.popleft()
            self._scheduled = more = bool(self._queue)
        if self.node.context.lockstep is not None:
            # handled from now on: the participant reports only when no callback runs
            self.node.context.lockstep.handled(self, item[1])
        if more:
            self.node.post(self)  # back in the queue, behind the work already waiting
        return self._take_message(*item)

    def _take_for_executor(self) -> Callable[[], Any] | None:
        """The executor takes the oldest queued message."""
        args = self.take_message()
        if args is None:
            return None
        callback = self.callback

        async def execute() -> None:
            await await_or_execute(callback, *args)

        return execute

    def _take_message(
        self, payload: bytes, attachment: bytes | None, received: int = 0
    ) -> tuple[Any, ...] | None:
        """The callback's arguments for one received message (None: not a valid one)."""
        # as rmw_zenoh, every publisher feeds every subscription whatever their QoS (its graph
        # cache does not enforce DDS's compatibility rules)
        message: Any = payload
        if not self.raw:
            try:
                message = self._codec.deserialize(payload)
            except Exception as exc:
                self.node.get_logger().error(
                    f"dropped a message on '{self.topic_name}' that is not a valid "
                    f"{self.type_name}: {exc}",
                    throttle_duration_sec=5.0,
                )
                return None
        if not self._with_info:
            return (message,)
        decoded = decode_attachment(attachment)
        self._received += 1
        info = MessageInfo(
            source_timestamp=decoded.timestamp_ns if decoded else 0,
            received_timestamp=received,
            publication_sequence_number=decoded.sequence if decoded else 0,
            reception_sequence_number=self._received,
            publisher_gid=decoded.gid if decoded else b"",
        )
        return (message, info)

    def destroy(self) -> None:
        """Undeclare the subscriber and its token."""
        self._undeclare(self._sub)
        self.node.forget(self)
