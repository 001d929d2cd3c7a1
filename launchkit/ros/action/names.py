"""The services and topics an action is made of, named as rcl_action names them.

An action ``/ns/fibonacci`` of type ``pkg/action/Fibonacci`` is three services and two topics
under ``/ns/fibonacci/_action/``; rmw_zenoh maps them like any other service or topic, so their
keys carry the types ``pkg::action::dds_::Fibonacci_SendGoal_`` and so on.
"""

from __future__ import annotations

ACTION_INFIX = "/_action/"
SEND_GOAL = "send_goal"
CANCEL_GOAL = "cancel_goal"
GET_RESULT = "get_result"
FEEDBACK = "feedback"
STATUS = "status"

CANCEL_GOAL_TYPE = "action_msgs/srv/CancelGoal"
STATUS_TYPE = "action_msgs/msg/GoalStatusArray"
FEEDBACK_SUFFIX = "_FeedbackMessage"


def part_name(action_name: str, part: str) -> str:
    """The name of one service or topic of an action: ``/fibonacci/_action/send_goal``."""
    return action_name.rstrip("/") + ACTION_INFIX + part


def action_of_feedback(topic: str, type_name: str) -> tuple[str, str] | None:
    """``(action name, action type)`` if ``topic`` of ``type_name`` is an action's feedback
    topic (how rcl_action finds actions in the graph), else None."""
    suffix = ACTION_INFIX + FEEDBACK
    if not topic.endswith(suffix) or not type_name.endswith(FEEDBACK_SUFFIX):
        return None
    return topic[: -len(suffix)], type_name[: -len(FEEDBACK_SUFFIX)]
