"""ROS 2 actions on launchkit's transport, as rclpy's ``rclpy.action`` (Jazzy) provides them.

An action is three services and two topics under ``<name>/_action/`` (``send_goal``,
``cancel_goal``, ``get_result``; ``feedback``, ``status``), carried like any other service or
topic in rmw_zenoh's wire format, so launchkit's and ROS 2's action servers and clients meet.
The classes load when first asked for: the CLI reads :mod:`.names` without the message types.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes

if TYPE_CHECKING:
    from launchkit.ros.action.client import ActionClient, ClientGoalHandle
    from launchkit.ros.action.goal_state import GoalEvent, GoalStatus
    from launchkit.ros.action.graph import (
        get_action_client_names_and_types_by_node,
        get_action_names_and_types,
        get_action_server_names_and_types_by_node,
    )
    from launchkit.ros.action.server import ActionServer, CancelResponse, GoalResponse
    from launchkit.ros.action.server_goal_handle import ServerGoalHandle

_WHERE = {
    "ActionClient": ".client",
    "ClientGoalHandle": ".client",
    "GoalEvent": ".goal_state",
    "GoalStatus": ".goal_state",
    "get_action_client_names_and_types_by_node": ".graph",
    "get_action_names_and_types": ".graph",
    "get_action_server_names_and_types_by_node": ".graph",
    "ActionServer": ".server",
    "CancelResponse": ".server",
    "GoalResponse": ".server",
    "ServerGoalHandle": ".server_goal_handle",
}
__all__ = [
    "ActionClient",
    "ActionServer",
    "CancelResponse",
    "ClientGoalHandle",
    "GoalEvent",
    "GoalResponse",
    "GoalStatus",
    "ServerGoalHandle",
    "get_action_client_names_and_types_by_node",
    "get_action_names_and_types",
    "get_action_server_names_and_types_by_node",
]
__getattr__ = lazy_attributes(__name__, _WHERE, globals())
