"""``rclpy.action.server``: the action server and its goal handles."""

from launchkit.ros.action.goal_state import GoalEvent
from launchkit.ros.action.server import (
    ActionServer,
    CancelResponse,
    GoalResponse,
    default_cancel_callback,
    default_goal_callback,
    default_handle_accepted_callback,
)
from launchkit.ros.action.server_goal_handle import ServerGoalHandle
from launchkit.ros.context import RCLError

__all__ = [
    "ActionServer",
    "CancelResponse",
    "GoalEvent",
    "GoalResponse",
    "RCLError",
    "ServerGoalHandle",
    "default_cancel_callback",
    "default_goal_callback",
    "default_handle_accepted_callback",
]
