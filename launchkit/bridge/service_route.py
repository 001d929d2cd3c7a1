"""One bridged service: a server on the side without one, forwarding to the real server.

rclpy (Jazzy 7.1) has no raw service API: ``Client.call_async`` and service callbacks take and
give message objects, and ``_rclpy.Client.send_request`` / ``Service.service_take_request``
convert through the Python type. So on the DDS side the bridge converts once with rclpy's own
``rclpy.serialization`` (the rmw's C serializer of the installed type support), and launchkit's
side stays raw: no launchkit decoding on either path.
"""

from __future__ import annotations

import threading
from typing import Any

from launchkit.bridge._rclpy import message_class
from launchkit.bridge.plan import ZENOH, ServiceRoute
from launchkit.bridge.topic_route import MissingTypeError
from launchkit.ros.msgs import get_service
from launchkit.ros.node import Node
from launchkit.ros.task import Future

CALL_TIMEOUT = 60.0  # seconds a forwarded call may take (launchkit's own client default)


class ServiceBridge:
    """Serves ``route.service`` on the side opposite ``route.source`` and forwards each call."""

    def __init__(self, route: ServiceRoute, zenoh_node: Node, dds_node: Any, group: Any) -> None:
        from rclpy.serialization import deserialize_message, serialize_message

        self.route = route
        self._serialize = serialize_message
        self._deserialize = deserialize_message
        self._zenoh_node = zenoh_node
        self._dds_node = dds_node
        dds_class = message_class(route.type_name)
        if dds_class is None:
            raise MissingTypeError(f"the rclpy install has no {route.type_name}")
        self._dds_class: Any = dds_class
        try:
            zenoh_class = get_service(route.type_name)
        except Exception:
            raise MissingTypeError(f"launchkit has no {route.type_name}") from None
        self._server: Any = None
        self._client: Any = None
        if route.source == ZENOH:
            self._client = zenoh_node.create_client(zenoh_class, route.service, raw=True)
            self._server = dds_node.create_service(
                self._dds_class, route.service, self._serve_dds, callback_group=group
            )
        else:
            self._client = dds_node.create_client(
                self._dds_class, route.service, callback_group=group
            )
            self._zenoh_class = zenoh_class

    @property
    def serving(self) -> bool:
        """Whether the bridge's server is up (on launchkit's side it waits for the DDS server
        to be matched, so that no request is sent before DDS could deliver it)."""
        return self._server is not None

    def poll(self) -> None:
        """Bring the launchkit-side server up once rclpy's client sees the DDS server."""
        if self._server is None and self._client.service_is_ready():
            self._server = self._zenoh_node.create_service(
                self._zenoh_class, self.route.service, self._serve_zenoh, raw=True
            )

    def _serve_dds(self, request: Any, response: Any) -> Any:
        # rclpy's executor thread (a reentrant group): block on launchkit's answer
        pending = self._client.call_async(self._serialize(request), CALL_TIMEOUT)
        if not pending.wait(CALL_TIMEOUT) or pending.exception() is not None:
            self._zenoh_node.get_logger().error(
                f"service '{self.route.service}' did not answer the bridged call: "
                f"{pending.exception() or 'timeout'}; sent an empty response"
            )
            return response
        return self._deserialize(pending.result(), self._dds_class.Response)

    def _serve_zenoh(self, request: bytes) -> Future:
        # launchkit's spinning thread: answer later, when DDS answers
        answer = Future()
        call = self._client.call_async(self._deserialize(request, self._dds_class.Request))

        def done(call: Any) -> None:
            timer.cancel()
            try:
                answer.set_result(self._serialize(call.result()))
            except Exception as exc:
                answer.set_exception(exc)

        def give_up() -> None:
            self._client.remove_pending_request(call)
            answer.set_exception(TimeoutError(f"no answer from DDS in {CALL_TIMEOUT} s"))

        timer = threading.Timer(CALL_TIMEOUT, give_up)
        timer.daemon = True
        timer.start()
        call.add_done_callback(done)
        return answer

    def close(self) -> None:
        """Undeclare the bridge's server and client."""
        if self.route.source == ZENOH:
            if self._server is not None:
                self._dds_node.destroy_service(self._server)
            self._zenoh_node.destroy_client(self._client)
        else:
            if self._server is not None:
                self._zenoh_node.destroy_service(self._server)
            self._dds_node.destroy_client(self._client)
