"""The ROS interface of a lifecycle node: its services and its ``~/transition_event`` topic
(lifecycle_msgs), as rcl_lifecycle offers them."""

from __future__ import annotations

from typing import Any, Protocol

from launchkit.ros import lifecycle_machine as sm
from launchkit.ros.msgs.lifecycle_msgs.msg import (
    State,
    Transition,
    TransitionDescription,
    TransitionEvent,
)
from launchkit.ros.msgs.lifecycle_msgs.srv import (
    ChangeState,
    GetAvailableStates,
    GetAvailableTransitions,
    GetState,
)
from launchkit.ros.topics import Publisher


class ManagedNode(Protocol):
    """What the services use of a lifecycle node (``launchkit.ros.lifecycle.LifecycleNode``)."""

    def create_publisher(self, msg_type: Any, topic: str, qos_profile: Any) -> Publisher:
        """A publisher."""

    def create_service(self, srv_type: Any, srv_name: str, callback: Any) -> Any:
        """A service."""

    def change_state(self, transition_id: int, label: str = "") -> bool:
        """Make a transition."""

    @property
    def current_state(self) -> Any:
        """The state (``state_id``, ``label``)."""


def _state(state_id: int) -> Any:
    return State(id=state_id, label=sm.STATE_LABELS[state_id])


def _description(transition: sm.Transition) -> Any:
    return TransitionDescription(
        transition=Transition(id=transition.id, label=transition.label),
        start_state=_state(transition.start),
        goal_state=_state(transition.goal),
    )


def transition_event(transition: sm.Transition, start: int, stamp_ns: int) -> Any:
    """The ``~/transition_event`` message for ``transition`` taken from ``start``."""
    return TransitionEvent(
        timestamp=stamp_ns,
        transition=Transition(id=transition.id, label=transition.label),
        start_state=_state(start),
        goal_state=_state(transition.goal),
    )


def serve_lifecycle(node: ManagedNode) -> Publisher:
    """Create the node's lifecycle services; its transition event publisher."""
    events = node.create_publisher(TransitionEvent, "~/transition_event", 10)

    def change_state(request: Any, response: Any) -> Any:
        transition = request.transition
        response.success = node.change_state(int(transition.id), str(transition.label))
        return response

    def get_state(_request: Any, response: Any) -> Any:
        response.current_state = _state(node.current_state.state_id)
        return response

    def get_available_states(_request: Any, response: Any) -> Any:
        response.available_states = [_state(s) for s in sm.STATE_LABELS]
        return response

    def get_available_transitions(_request: Any, response: Any) -> Any:
        state = node.current_state.state_id
        response.available_transitions = [_description(t) for t in sm.available(state)]
        return response

    def get_transition_graph(_request: Any, response: Any) -> Any:
        response.available_transitions = [_description(t) for t in sm.every_transition()]
        return response

    node.create_service(ChangeState, "~/change_state", change_state)
    node.create_service(GetState, "~/get_state", get_state)
    node.create_service(GetAvailableStates, "~/get_available_states", get_available_states)
    node.create_service(
        GetAvailableTransitions, "~/get_available_transitions", get_available_transitions
    )
    node.create_service(GetAvailableTransitions, "~/get_transition_graph", get_transition_graph)
    return events
