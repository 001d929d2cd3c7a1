"""``rotate_absolute``: one turtle's action server, and its goals as the turtle drives them.

As Jazzy's turtle: every goal and every cancel request is accepted and the goal executes at
once; a new goal aborts the one the turtle is turning for (``Rotation goal received before a
previous goal finished. Aborting previous goal``). The turtle's update does the rest
(:meth:`Turtle._drive_goal <launchkit.stock.turtlesim.world.Turtle>`): feedback ``remaining``
each step, and the end of the goal with its result ``delta``.
"""

from __future__ import annotations

from typing import Any

import launchkit.ros as ros
from launchkit.ros.action import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle
from launchkit.ros.msgs.turtlesim.action import RotateAbsolute
from launchkit.ros.task import Future
from launchkit.stock.turtlesim.world import Turtle


class Rotation:
    """An accepted goal, as the turtle sees it (:class:`RotationGoal
    <launchkit.stock.turtlesim.world.RotationGoal>`); ``done`` completes with its result."""

    def __init__(self, goal_handle: ServerGoalHandle) -> None:
        self._goal_handle = goal_handle
        self.done = Future()

    @property
    def theta(self) -> float:
        """The heading asked for, in radians."""
        return float(self._goal_handle.request.theta)

    def cancel_requested(self) -> bool:
        """Whether a client asked to cancel the goal."""
        return self._goal_handle.is_cancel_requested

    def feedback(self, remaining: float) -> None:
        """Send the feedback: radians still to turn."""
        self._goal_handle.publish_feedback(RotateAbsolute.Feedback(remaining=remaining))

    def succeed(self, delta: float) -> None:
        """End the goal as reached."""
        self._goal_handle.succeed()
        self.done.set_result(RotateAbsolute.Result(delta=delta))

    def canceled(self, delta: float) -> None:
        """End the goal as canceled."""
        self._goal_handle.canceled()
        self.done.set_result(RotateAbsolute.Result(delta=delta))

    def abort(self, delta: float) -> None:
        """End the goal as aborted."""
        self._goal_handle.abort()
        self.done.set_result(RotateAbsolute.Result(delta=delta))


def rotate_absolute_server(node: ros.Node, turtle: Turtle) -> ActionServer:
    """The action server ``<turtle>/rotate_absolute`` (turtlesim/action/RotateAbsolute)."""

    def accepted(goal_handle: ServerGoalHandle) -> None:
        goal_handle.execute()
        if turtle.accept_goal(Rotation(goal_handle)):
            node.get_logger().warn(
                "Rotation goal received before a previous goal finished. Aborting previous goal"
            )

    async def execute(goal_handle: ServerGoalHandle) -> Any:
        rotation = turtle.goal
        if not isinstance(rotation, Rotation) or rotation._goal_handle is not goal_handle:
            return RotateAbsolute.Result()  # aborted before it could execute
        return await rotation.done

    return ActionServer(
        node,
        RotateAbsolute,
        f"{turtle.name}/rotate_absolute",
        execute,
        goal_callback=lambda goal: GoalResponse.ACCEPT,
        cancel_callback=lambda goal_handle: CancelResponse.ACCEPT,
        handle_accepted_callback=accepted,
    )
