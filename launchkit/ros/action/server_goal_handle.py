"""``ServerGoalHandle``: one accepted goal as its action server's callbacks see it."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any, Protocol

from launchkit.ros.action.goal_state import ACTIVE, GoalEvent, GoalStatus, transition


class GoalOwner(Protocol):
    """What a goal handle needs of the :class:`~launchkit.ros.action.server.ActionServer`
    that made it."""

    @property
    def action_type(self) -> Any: ...

    def _publish_status(self) -> None: ...

    def _publish_feedback(self, message: Any) -> None: ...

    def _notify_goal_done(self, goal_handle: ServerGoalHandle) -> None: ...

    def _notify_execute(
        self, goal_handle: ServerGoalHandle, execute_callback: Callable[..., Any] | None
    ) -> None: ...


class ServerGoalHandle:
    """A goal the server accepted: its request, status, feedback and end (rclpy's).

    Made by :class:`ActionServer` only. ``execute()`` starts the execute callback;
    ``succeed()``, ``abort()`` and ``canceled()`` end the goal (the execute callback's return
    value is its result); every change of status is published on the action's status topic.
    """

    def __init__(self, action_server: GoalOwner, goal_info: Any, goal_request: Any) -> None:
        self._action_server = action_server
        self._goal_info = goal_info
        self._goal_request = goal_request
        self._status: GoalStatus | None = GoalStatus.STATUS_ACCEPTED  # None once destroyed
        self._lock = threading.Lock()

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ServerGoalHandle) and self.goal_id == other.goal_id

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = object.__hash__

    @property
    def request(self) -> Any:
        """The goal the client sent (``action_type.Goal``)."""
        return self._goal_request

    @property
    def goal_id(self) -> Any:
        """The goal's ``unique_identifier_msgs/msg/UUID``."""
        return self._goal_info.goal_id

    @property
    def goal_info(self) -> Any:
        """The goal's ``action_msgs/msg/GoalInfo`` (id and acceptance time)."""
        return self._goal_info

    @property
    def is_active(self) -> bool:
        """Accepted, executing or being canceled."""
        with self._lock:
            return self._status in ACTIVE

    @property
    def is_cancel_requested(self) -> bool:
        """A client asked to cancel and the server agreed (status CANCELING)."""
        return self.status == GoalStatus.STATUS_CANCELING

    @property
    def status(self) -> int:
        """The ``action_msgs/msg/GoalStatus`` value."""
        with self._lock:
            return int(GoalStatus.STATUS_UNKNOWN if self._status is None else self._status)

    def _update_state(self, event: GoalEvent) -> None:
        with self._lock:
            if self._status is None:
                return  # destroyed: ignored, as rclpy ignores it
            self._status = transition(self._status, event)
            done = self._status not in ACTIVE
        self._action_server._publish_status()
        if done:
            self._action_server._notify_goal_done(self)

    def execute(self, execute_callback: Callable[..., Any] | None = None) -> None:
        """Run the execute callback (``execute_callback``, else the server's) for this goal."""
        # a goal canceled before it executes stays CANCELING; the callback still runs and
        # sees is_cancel_requested
        if not self.is_cancel_requested:
            self._update_state(GoalEvent.EXECUTE)
        self._action_server._notify_execute(self, execute_callback)

    def publish_feedback(self, feedback: Any) -> None:
        """Send ``feedback`` (``action_type.Feedback``) to the clients."""
        action_type = self._action_server.action_type
        if not isinstance(feedback, action_type.Feedback):
            raise TypeError()
        with self._lock:
            if self._status is None:
                return
        message = action_type.Impl.FeedbackMessage()
        message.goal_id = self.goal_id
        message.feedback = feedback
        self._action_server._publish_feedback(message)

    def succeed(self) -> None:
        """End the goal as succeeded."""
        self._update_state(GoalEvent.SUCCEED)

    def abort(self) -> None:
        """End the goal as aborted."""
        self._update_state(GoalEvent.ABORT)

    def canceled(self) -> None:
        """End a goal being canceled as canceled."""
        self._update_state(GoalEvent.CANCELED)

    def destroy(self) -> None:
        """Forget the goal (its status becomes UNKNOWN)."""
        with self._lock:
            self._status = None
