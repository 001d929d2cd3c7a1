"""Services over Zenoh queryables and clients over ``get``, as rmw_zenoh maps them."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import zenoh

from launchkit.ros.keyexpr import decode_attachment, encode_attachment, entity_token, gid_of
from launchkit.ros.msgs import message_type_name, serialize, type_hash
from launchkit.ros.msgs._api import deserialize
from launchkit.ros.qos import QoSProfile, qos_profile_services_default
from launchkit.ros.task import Future

if TYPE_CHECKING:
    from launchkit.ros.node_interface import NodeInterface


class ServiceCallError(RuntimeError):
    """A service call that got no valid response."""


class _ServiceEntity:
    KIND = ""

    def __init__(self, node: NodeInterface, srv_type: Any, name: str) -> None:
        self.node = node
        self.srv_type = srv_type
        self.type_name = message_type_name(srv_type)
        self.srv_name = node.resolve_service_name(name)
        self.type_hash = type_hash(self.type_name)
        self.key = node.topic_key(self.srv_name, self.type_name, self.type_hash)
        qos: QoSProfile = qos_profile_services_default
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
        self._token: Any = node.context.session.liveliness().declare_token(self.token_key)

    def _undeclare(self, entity: Any) -> None:
        for item in (entity, self._token):
            try:
                item.undeclare()
            except Exception:  # the session may be closed already
                pass
        self.node.forget(self)


class Service(_ServiceEntity):
    """Answers requests: ``callback(request, response) -> response`` in the spinning thread."""

    KIND = "SS"

    def __init__(
        self, node: NodeInterface, srv_type: Any, name: str, callback: Callable[[Any, Any], Any]
    ) -> None:
        super().__init__(node, srv_type, name)
        self.callback = callback
        self._queryable = node.context.session.declare_queryable(
            self.key, self._on_query, complete=True
        )

    def _on_query(self, query: zenoh.Query) -> None:
        payload = query.payload
        attachment = query.attachment
        self.node.post(
            (
                self._handle,
                (
                    query,
                    b"" if payload is None else payload.to_bytes(),
                    None if attachment is None else attachment.to_bytes(),
                ),
            )
        )

    def _handle(self, query: zenoh.Query, payload: bytes, attachment: bytes | None) -> None:
        try:
            request = deserialize(payload, self.type_name + "_Request")
        except Exception as exc:
            query.reply_err(f"invalid {self.type_name} request: {exc}".encode())
            query.drop()  # type: ignore[no-untyped-call]
            return
        try:
            response = self.callback(request, self.srv_type.Response())
            if getattr(response, "__msgtype__", None) != self.type_name + "_Response":
                raise TypeError(
                    f"the callback of service '{self.srv_name}' returned "
                    f"{type(response).__name__}, expected {self.type_name}_Response"
                )
            data = serialize(response, self.type_name + "_Response")
        except Exception as exc:
            query.reply_err(f"service '{self.srv_name}' failed: {exc}".encode())
            query.drop()  # type: ignore[no-untyped-call]
            raise
        request_info = decode_attachment(attachment)
        sequence = request_info.sequence if request_info else 0
        gid = request_info.gid if request_info else self.gid
        query.reply(self.key, data, attachment=encode_attachment(sequence, time.time_ns(), gid))
        query.drop()  # type: ignore[no-untyped-call]

    def destroy(self) -> None:
        """Stop serving."""
        self._undeclare(self._queryable)


class Client(_ServiceEntity):
    """Calls a service: ``call(req)``, ``call_async(req)``, ``wait_for_service(timeout)``."""

    KIND = "SC"

    def __init__(self, node: NodeInterface, srv_type: Any, name: str) -> None:
        super().__init__(node, srv_type, name)
        self._sequence = 0
        self._lock = threading.Lock()

    def service_is_ready(self) -> bool:
        """Whether a server for this service exists now."""
        return any(
            t.type_name == self.type_name
            for t in self.node.context.graph.tokens("SS", self.srv_name)
        )

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Block until a server appears; False after ``timeout_sec``."""
        return self.node.context.graph.wait_for(self.service_is_ready, timeout_sec)

    def call_async(self, request: Any, timeout_sec: float = 60.0) -> Future:
        """Send ``request``; the future completes with the response (or an exception)."""
        if getattr(request, "__msgtype__", None) != self.type_name + "_Request":
            raise TypeError(
                f"client of '{self.srv_name}' expects {self.type_name}_Request, "
                f"got {type(request).__name__}"
            )
        future = Future(lambda item: self.node.post(item))
        with self._lock:
            self._sequence += 1
            attachment = encode_attachment(self._sequence, time.time_ns(), self.gid)
        response_type = self.type_name + "_Response"

        def on_reply(reply: zenoh.Reply) -> None:
            if reply.ok is not None:
                try:
                    future.set_result(deserialize(reply.ok.payload.to_bytes(), response_type))
                except Exception as exc:
                    future.set_exception(ServiceCallError(f"invalid response: {exc}"))
            elif reply.err is not None:
                future.set_exception(
                    ServiceCallError(reply.err.payload.to_string() or "service error")
                )

        def on_done() -> None:
            if not future.done():
                future.set_exception(
                    ServiceCallError(f"no response from service '{self.srv_name}'")
                )

        self.node.context.session.get(
            self.key,
            zenoh.handlers.Callback(on_reply, on_done),
            target=zenoh.QueryTarget.ALL_COMPLETE,
            payload=serialize(request, self.type_name + "_Request"),
            attachment=attachment,
            timeout=timeout_sec,
        )
        return future

    def call(self, request: Any, timeout_sec: float | None = None) -> Any:
        """Send ``request`` and block for the response (works with or without a spinner)."""
        future = self.call_async(request, timeout_sec or 60.0)
        if not future.wait(timeout_sec):
            future.cancel()
            raise ServiceCallError(f"service '{self.srv_name}' did not answer in {timeout_sec} s")
        return future.result()

    def destroy(self) -> None:
        """Forget the client."""
        self._undeclare(None)
