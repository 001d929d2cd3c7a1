"""Services over Zenoh queryables and clients over ``get``, as rmw_zenoh maps them."""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import zenoh

from launchkit.ros.keyexpr import decode_attachment, encode_attachment, entity_token, gid_of
from launchkit.ros.lockstep.participant import holding, stamp_ns
from launchkit.ros.logging import get_logger
from launchkit.ros.msgs import deserialize, message_type_name, serialize, type_hash
from launchkit.ros.qos import HistoryPolicy, QoSProfile
from launchkit.ros.task import Future, await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.node_interface import NodeInterface


class ServiceCallError(RuntimeError):
    """A service call that got no valid response."""


class _ServiceEntity:
    KIND = ""

    def __init__(
        self,
        node: NodeInterface,
        srv_type: Any,
        name: str,
        qos: QoSProfile,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        self.node = node
        # before anything can arrive: the executor asks the group of every ready entity
        self.callback_group = callback_group or node.default_callback_group
        self.callback_group.add_entity(self)
        self.srv_type = srv_type
        self.type_name = message_type_name(srv_type)
        self.srv_name = node.resolve_service_name(name)
        self.type_hash = type_hash(self.type_name)
        self.key = node.topic_key(self.srv_name, self.type_name, self.type_hash)
        self.qos_profile = qos
        self.token_key = entity_token(
            node.context.domain_id,
            node.zid,
            node.node_id,
            node.context.next_entity_id(),
            self.KIND,
            node.context.ros_args.enclave,
            node.get_namespace(),
            node.get_name(),
            self.srv_name,
            self.type_name,
            self.type_hash,
            qos,
        )
        self.gid = gid_of(self.token_key)
        self._token: Any = None

    def _announce(self) -> None:
        # after the queryable: a client that sees the token must find the server behind it
        self._token = self.node.context.session.liveliness().declare_token(self.token_key)

    def _undeclare(self, entity: Any) -> None:
        for item in (self._token, entity):
            try:
                item.undeclare()
            except Exception:  # the session may be closed already
                pass
        self.node.forget(self)


class Service(_ServiceEntity):
    """Answers requests: ``callback(request, response) -> response`` in the spinning thread.

    With ``raw=True`` (a launchkit extension, for bridges) the callback gets the request's CDR
    bytes and returns the response's, or a :class:`Future` that completes with them later.
    As in rmw_zenoh, at most ``depth`` requests wait for the callback under KEEP_LAST; a new one
    beyond that discards the oldest.
    """

    KIND = "SS"

    def __init__(
        self,
        node: NodeInterface,
        srv_type: Any,
        name: str,
        callback: Callable[..., Any],
        qos: QoSProfile,
        raw: bool = False,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, srv_type, name, qos, callback_group)
        self.callback = callback
        self.raw = raw
        self._pending: deque[tuple[zenoh.Query, bytes, bytes | None]] = deque()
        self._pending_lock = threading.Lock()
        self._scheduled = False  # the service waits in the node's work queue
        self._executor_event = False  # an executor's handler for it is pending
        self._queryable = node.context.session.declare_queryable(
            self.key, self._on_query, complete=True
        )
        self._announce()

    def _on_query(self, query: zenoh.Query) -> None:
        payload = query.payload
        attachment = query.attachment
        item = (
            query,
            b"" if payload is None else payload.to_bytes(),
            None if attachment is None else attachment.to_bytes(),
        )
        if self.node.context.lockstep is not None:
            self.node.context.lockstep.received(item[2])  # a request of a later instant
        qos = self.qos_profile.resolved()
        with self._pending_lock:
            if qos.history != HistoryPolicy.KEEP_ALL and len(self._pending) >= qos.effective_depth:
                oldest = self._pending.popleft()[0]
                get_logger("launchkit.ros").error(
                    f"Query queue depth of {qos.effective_depth} reached, discarding oldest "
                    f"Query for service '{self.srv_name}'"
                )
                oldest.drop()  # type: ignore[no-untyped-call]
            self._pending.append(item)
            if self._scheduled:
                return
            self._scheduled = True
        self.node.post(self)

    def _take_for_executor(self) -> Callable[[], Any] | None:
        """The executor takes the oldest waiting request (the service stays in the node's
        queue while more wait); the work answers it."""
        with self._pending_lock:
            if not self._pending:
                self._scheduled = False
                return None
            query, payload, attachment = self._pending.popleft()
            self._scheduled = bool(self._pending)
        if self._scheduled:
            self.node.post(self)

        async def execute() -> None:
            await self._handle(query, payload, attachment)

        return execute

    async def _handle(self, query: zenoh.Query, payload: bytes, attachment: bytes | None) -> None:
        request_info = decode_attachment(attachment)
        sequence = request_info.sequence if request_info else 0
        gid = request_info.gid if request_info else self.gid

        if self.node.context.refused is not None:
            return  # a request through another user's router gets no answer

        def reply(data: bytes) -> None:
            attachment = encode_attachment(sequence, stamp_ns(self.node.context), gid)
            query.reply(self.key, data, attachment=attachment)
            query.drop()  # type: ignore[no-untyped-call]

        def fail(message: str) -> None:
            query.reply_err(message.encode())
            query.drop()  # type: ignore[no-untyped-call]

        if self.raw:
            self._answer_raw(payload, reply, fail)
        else:
            await self._answer(payload, reply, fail)

    async def _answer(
        self, payload: bytes, reply: Callable[[bytes], None], fail: Callable[[str], None]
    ) -> None:
        try:
            request = deserialize(payload, self.type_name + "_Request")
        except Exception as exc:
            fail(f"invalid {self.type_name} request: {exc}")
            return
        await self._respond(request, reply, fail)

    async def _respond(
        self, request: Any, reply: Callable[[bytes], None], fail: Callable[[str], None]
    ) -> None:
        """Answer a valid request (a subclass may answer differently)."""
        try:
            response = await await_or_execute(self.callback, request, self.srv_type.Response())
            if getattr(response, "_TYPE_NAME", None) != self.type_name + "_Response":
                raise TypeError(
                    f"the callback of service '{self.srv_name}' returned "
                    f"{type(response).__name__}, expected {self.type_name}_Response"
                )
            data = serialize(response, self.type_name + "_Response")
        except Exception as exc:
            fail(f"service '{self.srv_name}' failed: {exc}")
            raise
        reply(data)

    def _answer_raw(
        self, payload: bytes, reply: Callable[[bytes], None], fail: Callable[[str], None]
    ) -> None:
        try:
            result = self.callback(payload)
        except Exception as exc:
            fail(f"service '{self.srv_name}' failed: {exc}")
            raise
        if not isinstance(result, Future):
            reply(bytes(result))
            return

        def done(future: Future) -> None:
            error = None if future.cancelled() else future.exception()
            if error is not None or future.cancelled():
                fail(f"service '{self.srv_name}' failed: {error or 'cancelled'}")
            else:
                reply(bytes(future.result()))

        result.add_done_callback(done)

    def destroy(self) -> None:
        """Stop serving."""
        self._undeclare(self._queryable)
        with self._pending_lock:
            pending, self._pending = list(self._pending), deque()
        for query, _, _ in pending:
            query.drop()  # type: ignore[no-untyped-call]


class Client(_ServiceEntity):
    """Calls a service: ``call(req)``, ``call_async(req)``, ``wait_for_service(timeout)``.

    A response completes its future as it arrives (Zenoh's thread), so ``call()`` needs no
    executor; the client then counts as ready in its node's executor (a ``spin_once`` returns
    for it, as rclpy's does when it takes a response), and the future's done callbacks run
    there.
    """

    KIND = "SC"

    def __init__(
        self,
        node: NodeInterface,
        srv_type: Any,
        name: str,
        qos: QoSProfile,
        raw: bool = False,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, srv_type, name, qos, callback_group)
        self.raw = raw
        self._executor_event = False  # an executor's handler for it is pending
        self._responded = False  # a response arrived that no executor has taken yet
        self._sequence = 0
        self._lock = threading.Lock()
        self._pending_requests: dict[int, Future] = {}
        self._announce()

    @property
    def service_name(self) -> str:
        """The resolved service name."""
        return self.srv_name

    def service_is_ready(self) -> bool:
        """Whether a server for this service exists now."""
        return any(
            t.type_name == self.type_name
            for t in self.node.context.graph.tokens("SS", self.srv_name)
        )

    def requests_in_flight(self) -> int:
        """How many requests await their reply (the lockstep waits for them)."""
        with self._lock:
            return len(self._pending_requests)

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Block until a server appears; False after ``timeout_sec``, or as soon as the context
        is no longer ok (a SIGINT or SIGTERM, as rclpy's wait stops)."""
        context = self.node.context
        with holding(context):  # in a lockstep launch the simulated time waits with it
            context.graph.wait_for(lambda: self.service_is_ready() or not context.ok(), timeout_sec)
        return self.service_is_ready()

    def call_async(self, request: Any, timeout_sec: float | None = None) -> Future:
        """Send ``request``; the future completes with the response.

        ``timeout_sec`` (a launchkit extension) fails the future with
        :class:`ServiceCallError` when no answer came in time; without it the call waits as
        long as a server may answer. A server's error also fails it. A raw client
        (``raw=True``) sends CDR bytes and completes with the response's bytes.
        """
        if self.raw:
            if not isinstance(request, (bytes, bytearray, memoryview)):
                raise TypeError(f"raw client of '{self.srv_name}' expects bytes")
            payload = bytes(request)
        elif getattr(request, "_TYPE_NAME", None) != self.type_name + "_Request":
            raise TypeError(
                f"client of '{self.srv_name}' expects {self.type_name}_Request, "
                f"got {type(request).__name__}"
            )
        else:
            payload = serialize(request, self.type_name + "_Request")
        future = Future(executor=self.node.scheduler)
        if self.node.context.refused is not None:  # nothing leaves for another user's router
            future.set_exception(ServiceCallError(self.node.context.refused.message))
            return future
        with self._lock:
            self._sequence += 1
            sequence = self._sequence
            self._pending_requests[sequence] = future
            attachment = encode_attachment(sequence, stamp_ns(self.node.context), self.gid)
        response_type = self.type_name + "_Response"

        def on_reply(reply: zenoh.Reply) -> None:
            with self._lock:
                if self._pending_requests.pop(sequence, None) is not future:
                    return  # given up (remove_pending_request), or answered already
            if reply.ok is not None:
                try:
                    data = reply.ok.payload.to_bytes()
                    future.set_result(data if self.raw else deserialize(data, response_type))
                except Exception as exc:
                    future.set_exception(ServiceCallError(f"invalid response: {exc}"))
            elif reply.err is not None:
                future.set_exception(
                    ServiceCallError(reply.err.payload.to_string() or "service error")
                )
            self._ready()

        def on_done() -> None:
            with self._lock:
                if self._pending_requests.pop(sequence, None) is not future:
                    return
            future.set_exception(ServiceCallError(f"no response from service '{self.srv_name}'"))
            self._ready()

        self.node.context.session.get(
            self.key,
            zenoh.handlers.Callback(on_reply, on_done),
            target=zenoh.QueryTarget.ALL_COMPLETE,
            payload=payload,
            attachment=attachment,
            timeout=_FOREVER if timeout_sec is None else timeout_sec,
        )
        return future

    def _ready(self) -> None:
        with self._lock:
            if self._responded:
                return
            self._responded = True
        self.node.post(self)

    def _take_for_executor(self) -> Callable[[], Any] | None:
        """The response was delivered already: nothing left to run."""
        with self._lock:
            self._responded = False
        return None

    def call(self, request: Any, timeout_sec: float | None = None) -> Any:
        """Send ``request`` and block for the response; None after ``timeout_sec`` (rclpy's).

        Works with or without a spinning executor (the response does not need one).
        """
        future = self.call_async(request)
        if not future.wait(timeout_sec):
            self.remove_pending_request(future)
        exception = future.exception()
        if exception is not None:
            raise exception
        return future.result()

    def remove_pending_request(self, future: Future) -> None:
        """Forget the request of ``future``: its response, if any, is dropped."""
        with self._lock:
            for sequence, pending in list(self._pending_requests.items()):
                if pending is future:
                    del self._pending_requests[sequence]

    def destroy(self) -> None:
        """Forget the client."""
        self._undeclare(None)


_FOREVER = 10.0 * 365 * 24 * 3600  # Zenoh's queries need a deadline; rclpy's calls have none
