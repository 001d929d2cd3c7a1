"""``ActionServer``: goals, feedback, cancel and results over three services and two topics,
as rclpy's action server behaves (Jazzy)."""

from __future__ import annotations

import enum
import threading
import time
import traceback
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.ros.action import names
from launchkit.ros.action.deferred_service import DeferredService
from launchkit.ros.action.goal_state import CANCELABLE, GoalEvent, GoalStatus
from launchkit.ros.action.server_goal_handle import ServerGoalHandle
from launchkit.ros.context import RCLError
from launchkit.ros.msgs import get_message
from launchkit.ros.qos import (
    QoSProfile,
    qos_profile_action_status_default,
    qos_profile_services_default,
)
from launchkit.ros.task import Future, await_or_execute

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import CallbackGroup
    from launchkit.ros.node import Node


class GoalResponse(enum.Enum):
    """What a goal callback answers."""

    REJECT = 1
    ACCEPT = 2


class CancelResponse(enum.Enum):
    """What a cancel callback answers."""

    REJECT = 1
    ACCEPT = 2


def default_handle_accepted_callback(goal_handle: ServerGoalHandle) -> None:
    """Execute the goal at once."""
    goal_handle.execute()


def default_goal_callback(goal_request: Any) -> GoalResponse:
    """Accept every goal."""
    return GoalResponse.ACCEPT


def default_cancel_callback(cancel_request: Any) -> CancelResponse:
    """Refuse every cancel request."""
    return CancelResponse.REJECT


_CANCEL_ERROR_NONE = 0
_CANCEL_ERROR_UNKNOWN_GOAL_ID = 2
_CANCEL_ERROR_GOAL_TERMINATED = 3


class ActionServer:
    """Serves action ``action_name`` of ``action_type`` on ``node`` (rclpy's signature).

    A goal request goes to ``goal_callback`` (accept or reject); an accepted goal to
    ``handle_accepted_callback`` (by default: execute it now), whose ``goal_handle.execute()``
    runs ``execute_callback(goal_handle)`` as a task of the node's executor; its return value is
    the result, kept for ``result_timeout`` seconds after the goal ends. Cancel requests go to
    ``cancel_callback(goal_handle)``. Callbacks may be coroutine functions; the three services
    run in ``callback_group``.
    """

    def __init__(
        self,
        node: Node,
        action_type: Any,
        action_name: str,
        execute_callback: Callable[..., Any],
        *,
        callback_group: CallbackGroup | None = None,
        goal_callback: Callable[..., Any] = default_goal_callback,
        handle_accepted_callback: Callable[..., Any] = default_handle_accepted_callback,
        cancel_callback: Callable[..., Any] = default_cancel_callback,
        goal_service_qos_profile: QoSProfile = qos_profile_services_default,
        result_service_qos_profile: QoSProfile = qos_profile_services_default,
        cancel_service_qos_profile: QoSProfile = qos_profile_services_default,
        feedback_pub_qos_profile: QoSProfile | None = None,
        status_pub_qos_profile: QoSProfile = qos_profile_action_status_default,
        result_timeout: float = 900,
    ) -> None:
        self.callback_group = callback_group or node.default_callback_group
        self._lock = threading.RLock()
        self.register_handle_accepted_callback(handle_accepted_callback)
        self.register_goal_callback(goal_callback)
        self.register_cancel_callback(cancel_callback)
        self.register_execute_callback(execute_callback)
        self._node = node
        self._action_type = action_type
        self._action_name = node.resolve_topic_name(action_name)
        self._result_timeout = result_timeout
        self._goal_handles: dict[bytes, ServerGoalHandle] = {}
        self._result_futures: dict[bytes, Future] = {}
        self._done_at: dict[bytes, float] = {}  # monotonic time each finished goal ended
        self._goal_info_type = get_message("action_msgs/msg/GoalInfo")
        self._goal_status_type = get_message("action_msgs/msg/GoalStatus")
        impl = action_type.Impl
        self._services = [
            node.create_service(
                service_type,
                names.part_name(self._action_name, part),
                callback,
                qos_profile=qos,
                callback_group=self.callback_group,
                service_class=DeferredService,
            )
            for service_type, part, callback, qos in (
                (impl.SendGoalService, names.SEND_GOAL, self._on_goal_request,
                 goal_service_qos_profile),
                (impl.CancelGoalService, names.CANCEL_GOAL, self._on_cancel_request,
                 cancel_service_qos_profile),
                (impl.GetResultService, names.GET_RESULT, self._on_result_request,
                 result_service_qos_profile),
            )
        ]  # fmt: skip
        self._feedback_publisher = node.create_publisher(
            impl.FeedbackMessage,
            names.part_name(self._action_name, names.FEEDBACK),
            feedback_pub_qos_profile or QoSProfile(depth=10),
        )
        self._status_publisher = node.create_publisher(
            impl.GoalStatusMessage,
            names.part_name(self._action_name, names.STATUS),
            status_pub_qos_profile,
        )
        self._expire_timer = node.create_timer(
            max(result_timeout / 10.0, 0.01),
            self._expire_goals,
            callback_group=self.callback_group,
            autostart=False,
        )
        node.add_waitable(self)
        self._logger = node.get_logger().get_child("action_server")

    @property
    def action_type(self) -> Any:
        """The action's type."""
        return self._action_type

    @property
    def action_name(self) -> str:
        """The resolved action name."""
        return self._action_name

    # the three services ---------------------------------------------------------------------
    async def _on_goal_request(self, request: Any, respond: Callable[[Any], None]) -> None:
        goal_uuid = bytes(request.goal_id.uuid)
        goal_info = self._goal_info_type(goal_id=request.goal_id)
        self._logger.debug(f"New goal request with ID: {list(goal_uuid)}")
        with self._lock:
            exists = goal_uuid in self._goal_handles
        accepted = False
        if not exists:
            answer = await await_or_execute(self._goal_callback, request.goal)
            if not isinstance(answer, GoalResponse):
                self._logger.warning(
                    "Goal request callback did not return a GoalResponse type. Rejecting goal."
                )
            else:
                accepted = answer == GoalResponse.ACCEPT
        goal_handle = None
        if accepted:
            goal_info.stamp = self._node.get_clock().now().to_msg()
            goal_handle = ServerGoalHandle(self, goal_info, request.goal)
            with self._lock:
                self._goal_handles[goal_uuid] = goal_handle
                self._result_futures[goal_uuid] = Future()
        response = self._action_type.Impl.SendGoalService.Response()
        response.accepted = accepted
        response.stamp = goal_info.stamp
        respond(response)
        if goal_handle is None:
            self._logger.debug(f"New goal rejected: {list(goal_uuid)}")
            return
        self._logger.debug(f"New goal accepted: {list(goal_uuid)}")
        await await_or_execute(self._handle_accepted_callback, goal_handle)

    async def _on_cancel_request(self, request: Any, respond: Callable[[Any], None]) -> None:
        self._logger.debug(f"Cancel request received: {request}")
        response = self._action_type.Impl.CancelGoalService.Response()
        with self._lock:
            candidates, response.return_code = self._goals_to_cancel(request.goal_info)
        canceling = []
        for goal_handle in candidates:
            answer = await await_or_execute(self._cancel_callback, goal_handle)
            if answer != CancelResponse.ACCEPT:
                continue
            try:
                goal_handle._update_state(GoalEvent.CANCEL_GOAL)
            except RCLError as exc:  # it ended while the callback decided
                self._logger.debug(f"Failed to cancel goal in cancel callback: {exc}")
                continue
            canceling.append(goal_handle.goal_info)
        response.goals_canceling = canceling
        respond(response)

    def _goals_to_cancel(self, wanted: Any) -> tuple[list[ServerGoalHandle], int]:
        """The goals a cancel request names, and its return code (rcl_action's rules: a goal
        id alone is that goal; a stamp alone is every goal accepted at or before it; both is
        both; neither is every goal)."""
        goal_uuid = bytes(wanted.goal_id.uuid)
        stamp_ns = wanted.stamp.sec * 1_000_000_000 + wanted.stamp.nanosec
        handles = list(self._goal_handles.values())
        if any(goal_uuid) and stamp_ns == 0:
            for handle in handles:
                if bytes(handle.goal_id.uuid) == goal_uuid:
                    if handle.status in CANCELABLE:
                        return [handle], _CANCEL_ERROR_NONE
                    return [], _CANCEL_ERROR_GOAL_TERMINATED
            return [], _CANCEL_ERROR_UNKNOWN_GOAL_ID
        if not any(goal_uuid) and stamp_ns == 0:
            stamp_ns = 2**63 - 1
        found = []
        for handle in handles:
            accepted = handle.goal_info.stamp
            accepted_ns = accepted.sec * 1_000_000_000 + accepted.nanosec
            if handle.status in CANCELABLE and (
                accepted_ns <= stamp_ns or bytes(handle.goal_id.uuid) == goal_uuid
            ):
                found.append(handle)
        return found, _CANCEL_ERROR_NONE

    async def _on_result_request(self, request: Any, respond: Callable[[Any], None]) -> None:
        goal_uuid = bytes(request.goal_id.uuid)
        self._logger.debug(f"Result request received for goal with ID: {list(goal_uuid)}")
        with self._lock:
            future = self._result_futures.get(goal_uuid)
        if future is None:
            self._logger.debug(f"Sending result response for unknown goal ID: {list(goal_uuid)}")
            response = self._action_type.Impl.GetResultService.Response()
            response.status = GoalStatus.STATUS_UNKNOWN
            respond(response)
            return
        # answered when the goal ends, in the thread that ends it
        future.add_done_callback(lambda done: respond(done.result()))

    # what goal handles call -----------------------------------------------------------------
    def _notify_execute(
        self, goal_handle: ServerGoalHandle, execute_callback: Callable[..., Any] | None
    ) -> None:
        callback = execute_callback or self._execute_callback
        scheduler = self._node.executor or self._node.scheduler
        scheduler.create_task(self._execute_goal, callback, goal_handle)

    async def _execute_goal(
        self, execute_callback: Callable[..., Any], goal_handle: ServerGoalHandle
    ) -> None:
        goal_uuid = bytes(goal_handle.goal_id.uuid)
        self._logger.debug(f"Executing goal with ID {list(goal_uuid)}")
        try:
            result = await await_or_execute(execute_callback, goal_handle)
        except Exception as exc:
            result = self._action_type.Result()
            self._logger.error(f"Error raised in execute callback: {exc}")
            traceback.print_exc()
        if goal_handle.is_active:
            self._logger.warning(
                f"Goal state not set, assuming aborted. Goal ID: {list(goal_uuid)}"
            )
            goal_handle.abort()
        self._logger.debug(
            f"Goal with ID {list(goal_uuid)} finished with state {goal_handle.status}"
        )
        if not isinstance(result, self._action_type.Result):
            self._logger.error(
                f"The execute callback returned {type(result).__name__}, expected "
                f"{self._action_type.Result.__name__}: the result is empty"
            )
            result = self._action_type.Result()
        response = self._action_type.Impl.GetResultService.Response()
        response.status = goal_handle.status
        response.result = result
        with self._lock:
            future = self._result_futures.get(goal_uuid)
        if future is not None:
            future.set_result(response)

    def _publish_feedback(self, message: Any) -> None:
        self._feedback_publisher.publish(message)

    def _publish_status(self) -> None:
        with self._lock:
            handles = list(self._goal_handles.values())
        message = self._action_type.Impl.GoalStatusMessage()
        message.status_list = [
            self._goal_status_type(goal_info=h.goal_info, status=h.status) for h in handles
        ]
        self._status_publisher.publish(message)

    def _notify_goal_done(self, goal_handle: ServerGoalHandle) -> None:
        with self._lock:
            self._done_at[bytes(goal_handle.goal_id.uuid)] = time.monotonic()
        if self._expire_timer.is_canceled():
            self._expire_timer.reset()
            self._node.wake()  # a spin blocked without timers must see it

    def _expire_goals(self) -> None:
        """Forget the goals that ended more than ``result_timeout`` ago (their results too)."""
        deadline = time.monotonic() - self._result_timeout
        with self._lock:
            expired = [uuid for uuid, at in self._done_at.items() if at <= deadline]
            for goal_uuid in expired:
                self._goal_handles.pop(goal_uuid).destroy()
                del self._result_futures[goal_uuid]
                del self._done_at[goal_uuid]
            idle = not self._done_at
        if idle:
            self._expire_timer.cancel()

    # rclpy's registration API -----------------------------------------------------------------
    def register_handle_accepted_callback(self, callback: Callable[..., Any] | None) -> None:
        """Replace the accepted-goal callback (None: execute at once)."""
        self._handle_accepted_callback = callback or default_handle_accepted_callback

    def register_goal_callback(self, callback: Callable[..., Any] | None) -> None:
        """Replace the goal callback (None: accept every goal)."""
        self._goal_callback = callback or default_goal_callback

    def register_cancel_callback(self, callback: Callable[..., Any] | None) -> None:
        """Replace the cancel callback (None: refuse every cancel request)."""
        self._cancel_callback = callback or default_cancel_callback

    def register_execute_callback(self, callback: Callable[..., Any]) -> None:
        """Replace the execute callback."""
        if not callable(callback):
            raise TypeError("Failed to register goal execution callback: not callable")
        self._execute_callback = callback

    def destroy(self) -> None:
        """Stop serving: the services, topics and goals go."""
        with self._lock:
            handles = list(self._goal_handles.values())
        for handle in handles:
            handle.destroy()
        for service in self._services:
            self._node.destroy_service(service)
        self._node.destroy_publisher(self._feedback_publisher)
        self._node.destroy_publisher(self._status_publisher)
        self._node.destroy_timer(self._expire_timer)
        if self in self._node.waitables:
            self._node.remove_waitable(self)
