"""``ActionClient`` and ``ClientGoalHandle``: sending goals, following them, canceling them,
as rclpy's action client does (Jazzy)."""

from __future__ import annotations

import threading
import uuid
import weakref
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.ros.action import names
from launchkit.ros.action.goal_state import ACTIVE, GoalStatus
from launchkit.ros.lockstep.participant import holding
from launchkit.ros.msgs import get_message, get_service, message_type_name
from launchkit.ros.qos import (
    QoSProfile,
    qos_profile_action_status_default,
    qos_profile_services_default,
)
from launchkit.ros.task import Future, await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.node import Node
    from launchkit.ros.services import Client


#: finished goals whose feedback callbacks an action client keeps
_FINISHED_KEPT = 32


class ClientGoalHandle:
    """A goal this client sent, once the server answered (accepted or not)."""

    def __init__(self, action_client: ActionClient, goal_id: Any, goal_response: Any) -> None:
        self._action_client = action_client
        self._goal_id = goal_id
        self._goal_response = goal_response
        self._status = int(GoalStatus.STATUS_UNKNOWN)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClientGoalHandle) and self._goal_id == other.goal_id

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = object.__hash__

    def __repr__(self) -> str:
        return (
            f"ClientGoalHandle <id={self.goal_id.uuid}, accepted={self.accepted}, "
            f"status={self.status}>"
        )

    @property
    def goal_id(self) -> Any:
        """The goal's ``unique_identifier_msgs/msg/UUID``."""
        return self._goal_id

    @property
    def stamp(self) -> Any:
        """When the server accepted the goal."""
        return self._goal_response.stamp

    @property
    def accepted(self) -> bool:
        """Whether the server accepted the goal."""
        return bool(self._goal_response.accepted)

    @property
    def status(self) -> int:
        """The last status the server published for the goal."""
        return self._status

    def cancel_goal(self) -> Any:
        """Ask to cancel the goal and wait for the answer (``CancelGoal.Response``)."""
        return self._action_client._cancel_goal(self)

    def cancel_goal_async(self) -> Future:
        """Ask to cancel the goal; the future completes with the server's answer."""
        return self._action_client._cancel_goal_async(self)

    def get_result(self) -> Any:
        """Wait for the goal's end and return ``GetResult.Response`` (status and result)."""
        return self._action_client._get_result(self)

    def get_result_async(self) -> Future:
        """The future of the goal's ``GetResult.Response`` (status and result)."""
        return self._action_client._get_result_async(self)


class ActionClient:
    """Sends goals to action ``action_name`` of ``action_type`` (rclpy's signature).

    ``send_goal_async(goal, feedback_callback=)`` returns a future completed, in the node's
    executor, with a :class:`ClientGoalHandle`; feedback and status arrive on the client's
    ``callback_group``.
    """

    def __init__(
        self,
        node: Node,
        action_type: Any,
        action_name: str,
        *,
        callback_group: CallbackGroup | None = None,
        goal_service_qos_profile: QoSProfile = qos_profile_services_default,
        result_service_qos_profile: QoSProfile = qos_profile_services_default,
        cancel_service_qos_profile: QoSProfile = qos_profile_services_default,
        feedback_sub_qos_profile: QoSProfile | None = None,
        status_sub_qos_profile: QoSProfile = qos_profile_action_status_default,
    ) -> None:
        self.callback_group = callback_group or node.default_callback_group
        self._node = node
        self._action_type = action_type
        self._action_name = node.resolve_topic_name(action_name)
        self._goal_handles: dict[bytes, weakref.ref[ClientGoalHandle]] = {}
        self._feedback_callbacks: dict[bytes, Callable[..., Any]] = {}
        # the goals whose result is in, oldest first: their feedback callbacks are kept a while,
        # as feedback published before the result may still be on its way (another key, another
        # Zenoh thread), then forgotten (rclpy forgets them with the result)
        self._finished: deque[bytes] = deque()
        # the feedback of goals sent and not yet answered, in order of arrival: Zenoh may bring
        # a goal's first feedback before the response accepting it (another key, another
        # thread); it is held until the response has been handled, as the server sent them
        self._early_feedback: dict[bytes, list[Any]] = {}
        self._feedback_lock = threading.Lock()
        self._uuid_type = get_message("unique_identifier_msgs/msg/UUID")
        self._cancel_type = get_service(names.CANCEL_GOAL_TYPE)
        impl = action_type.Impl

        def client(service_type: Any, part: str, qos: QoSProfile) -> Client:
            return node.create_client(
                service_type,
                names.part_name(self._action_name, part),
                qos_profile=qos,
                callback_group=self.callback_group,
            )

        self._goal_client = client(impl.SendGoalService, names.SEND_GOAL, goal_service_qos_profile)
        self._cancel_client = client(
            impl.CancelGoalService, names.CANCEL_GOAL, cancel_service_qos_profile
        )
        self._result_client = client(
            impl.GetResultService, names.GET_RESULT, result_service_qos_profile
        )
        self._feedback_subscription = node.create_subscription(
            impl.FeedbackMessage,
            names.part_name(self._action_name, names.FEEDBACK),
            self._on_feedback,
            feedback_sub_qos_profile or QoSProfile(depth=10),
            callback_group=self.callback_group,
        )
        self._status_subscription = node.create_subscription(
            impl.GoalStatusMessage,
            names.part_name(self._action_name, names.STATUS),
            self._on_status,
            status_sub_qos_profile,
            callback_group=self.callback_group,
        )
        self._feedback_type = message_type_name(impl.FeedbackMessage)
        node.add_waitable(self)
        self._logger = node.get_logger().get_child("action_client")

    @property
    def action_name(self) -> str:
        """The resolved action name."""
        return self._action_name

    # goals ------------------------------------------------------------------------------------
    def _goal_request(self, goal: Any, feedback_callback: Any, goal_uuid: Any) -> Any:
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError()
        request = self._action_type.Impl.SendGoalService.Request()
        request.goal_id = (
            self._uuid_type(uuid=list(uuid.uuid4().bytes)) if goal_uuid is None else goal_uuid
        )
        request.goal = goal
        if feedback_callback is not None:
            goal_uuid = bytes(request.goal_id.uuid)
            with self._feedback_lock:
                self._feedback_callbacks[goal_uuid] = feedback_callback
                self._early_feedback[goal_uuid] = []
        return request

    def _goal_handle(self, goal_id: Any, response: Any) -> ClientGoalHandle:
        goal_handle = ClientGoalHandle(self, goal_id, response)
        if goal_handle.accepted:
            goal_uuid = bytes(goal_id.uuid)
            if goal_uuid in self._goal_handles and self._goal_handles[goal_uuid]() is not None:
                raise RuntimeError(f"Two goals were accepted with the same ID ({goal_handle})")
            self._goal_handles[goal_uuid] = weakref.ref(goal_handle)
        return goal_handle

    def send_goal_async(
        self,
        goal: Any,
        feedback_callback: Callable[..., Any] | None = None,
        goal_uuid: Any = None,
    ) -> Future:
        """Send ``goal``; the future completes with a :class:`ClientGoalHandle` once the server
        accepted or rejected it. ``feedback_callback(feedback_message)`` gets the goal's
        feedback (an ``Impl.FeedbackMessage``: ``.goal_id`` and ``.feedback``)."""
        request = self._goal_request(goal, feedback_callback, goal_uuid)
        future = Future(executor=self._node.scheduler)

        def answered(call: Future) -> None:
            try:
                complete(call)
            finally:
                self._release_early_feedback(request)

        def complete(call: Future) -> None:
            if call.cancelled():
                future.cancel()
                return
            error = call.exception()
            if error is not None:
                future.set_exception(error)
                return
            try:
                future.set_result(self._goal_handle(request.goal_id, call.result()))
            except RuntimeError as exc:
                future.set_exception(exc)

        call = self._goal_client.call_async(request)
        # completed where the response arrives, so that its done callbacks are queued in the
        # node's executor as rclpy queues them when it takes the response: ahead of feedback
        # that arrives after it
        call._add_waiter(lambda: answered(call))
        return future

    def send_goal(self, goal: Any, **kwargs: Any) -> Any:
        """Send ``goal`` and wait for its end: the ``GetResult.Response`` (status, result)."""
        request = self._goal_request(goal, kwargs.get("feedback_callback"), kwargs.get("goal_uuid"))
        try:
            response = self._goal_client.call(request)
        finally:
            self._release_early_feedback(request)
        return self._get_result(self._goal_handle(request.goal_id, response))

    # cancel and result --------------------------------------------------------------------------
    def _cancel_goal_async(self, goal_handle: ClientGoalHandle) -> Future:
        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError(f"Expected type ClientGoalHandle but received {type(goal_handle)}")
        request = self._cancel_type.Request()
        request.goal_info.goal_id = goal_handle.goal_id
        return self._cancel_client.call_async(request)

    def _cancel_goal(self, goal_handle: ClientGoalHandle) -> Any:
        return _wait(self._cancel_goal_async(goal_handle))

    def _get_result_async(self, goal_handle: ClientGoalHandle) -> Future:
        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError(f"Expected type ClientGoalHandle but received {type(goal_handle)}")
        request = self._action_type.Impl.GetResultService.Request()
        request.goal_id = goal_handle.goal_id
        goal_uuid = bytes(goal_handle.goal_id.uuid)
        future = self._result_client.call_async(request)
        future.add_done_callback(lambda _: self._forget_feedback(goal_uuid))
        return future

    def _get_result(self, goal_handle: ClientGoalHandle) -> Any:
        return _wait(self._get_result_async(goal_handle))

    # topics -----------------------------------------------------------------------------------
    def _forget_feedback(self, goal_uuid: bytes) -> None:
        """A goal's result is in: forget the feedback callback of the oldest finished goal
        beyond the last :data:`_FINISHED_KEPT`."""
        with self._feedback_lock:
            self._finished.append(goal_uuid)
            while len(self._finished) > _FINISHED_KEPT:
                self._feedback_callbacks.pop(self._finished.popleft(), None)

    async def _on_feedback(self, message: Any) -> None:
        goal_uuid = bytes(message.goal_id.uuid)
        with self._feedback_lock:
            early = self._early_feedback.get(goal_uuid)
            if early is not None:
                early.append(message)
                return
            callback = self._feedback_callbacks.get(goal_uuid)
        if callback is not None:
            await await_or_execute(callback, message)

    def _release_early_feedback(self, request: Any) -> None:
        """The goal's response is in (or its call failed): hand the feedback that came before
        it to the executor, after the callbacks of the goal's future."""
        goal_uuid = bytes(request.goal_id.uuid)
        if goal_uuid in self._early_feedback:
            self._node.scheduler.create_task(self._deliver_early_feedback, goal_uuid)

    async def _deliver_early_feedback(self, goal_uuid: bytes) -> None:
        # one at a time: feedback arriving meanwhile is still held, and comes after
        while True:
            with self._feedback_lock:
                early = self._early_feedback.get(goal_uuid)
                if not early:
                    self._early_feedback.pop(goal_uuid, None)
                    return
                message = early.pop(0)
                callback = self._feedback_callbacks.get(goal_uuid)
            if callback is not None:
                await await_or_execute(callback, message)

    def _on_status(self, message: Any) -> None:
        for goal_status in message.status_list:
            goal_uuid = bytes(goal_status.goal_info.goal_id.uuid)
            ref = self._goal_handles.get(goal_uuid)
            if ref is None:
                continue
            goal_handle = ref()
            if goal_handle is not None:
                goal_handle._status = goal_status.status
            if goal_handle is None or goal_status.status not in ACTIVE:
                self._goal_handles.pop(goal_uuid, None)

    # the server -------------------------------------------------------------------------------
    def server_is_ready(self) -> bool:
        """Whether a server of this action is there: its three services and two topics."""
        graph = self._node.context.graph
        impl = self._action_type.Impl
        needed = (
            ("SS", names.SEND_GOAL, message_type_name(impl.SendGoalService)),
            ("SS", names.CANCEL_GOAL, names.CANCEL_GOAL_TYPE),
            ("SS", names.GET_RESULT, message_type_name(impl.GetResultService)),
            ("MP", names.FEEDBACK, self._feedback_type),
            ("MP", names.STATUS, names.STATUS_TYPE),
        )
        return all(
            any(
                t.type_name == type_name
                for t in graph.tokens(kind, names.part_name(self._action_name, part))
            )
            for kind, part, type_name in needed
        )

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        """Block until a server is ready; False after ``timeout_sec`` or at shutdown."""
        context = self._node.context
        with holding(context):  # in a lockstep launch the simulated time waits with it
            context.graph.wait_for(lambda: self.server_is_ready() or not context.ok(), timeout_sec)
        return self.server_is_ready()

    def destroy(self) -> None:
        """Forget the client: its services' clients and subscriptions go."""
        for client in (self._goal_client, self._cancel_client, self._result_client):
            self._node.destroy_client(client)
        self._node.destroy_subscription(self._feedback_subscription)
        self._node.destroy_subscription(self._status_subscription)
        if self in self._node.waitables:
            self._node.remove_waitable(self)


def _wait(future: Future) -> Any:
    future.wait()
    error = future.exception()
    if error is not None:
        raise error
    return future.result()
