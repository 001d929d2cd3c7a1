"""Lifecycle nodes: ``LifecycleNode`` (launch_ros), the ``ChangeState`` event that asks one to
make a transition, and the ``StateTransition`` event each of its transitions emits.

The node runs like any ``<node>``; through the launcher's ROS node (the context's ROS link)
the action follows the node's ``~/transition_event`` topic and serves ChangeState events by
calling its ``~/change_state`` service, as launch_ros does.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.description.actions.node import ExecuteNode
from launchkit.description.events import Event, EventHandler
from launchkit.description.substitutions.base import perform
from launchkit.errors import RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext

#: lifecycle_msgs/msg/Transition requests, by id (what ROS logs when one fails)
TRANSITIONS = {
    0: "TRANSITION_CREATE",
    1: "TRANSITION_CONFIGURE",
    2: "TRANSITION_CLEANUP",
    3: "TRANSITION_ACTIVATE",
    4: "TRANSITION_DEACTIVATE",
    5: "TRANSITION_UNCONFIGURED_SHUTDOWN",
    6: "TRANSITION_INACTIVE_SHUTDOWN",
    7: "TRANSITION_ACTIVE_SHUTDOWN",
    8: "TRANSITION_DESTROY",
}


class ChangeState(Event):
    """Ask the lifecycle nodes ``lifecycle_node_matcher`` accepts to make ``transition_id``."""

    name = "launch_ros.events.lifecycle.ChangeState"

    def __init__(
        self, *, lifecycle_node_matcher: Callable[[Any], bool], transition_id: int
    ) -> None:
        if transition_id not in TRANSITIONS:
            known = ", ".join(f"{k}: {v}" for k, v in TRANSITIONS.items())
            raise ValueError(f"transition_id {transition_id} is not one of {{{known}}}")
        self.lifecycle_node_matcher = lifecycle_node_matcher
        self.transition_id = transition_id


class StateTransition(Event):
    """A lifecycle node made a transition (a ``~/transition_event`` message): ``transition``,
    ``start_state`` and ``goal_state`` are labels (``configure``, ``unconfigured``...)."""

    name = "launch_ros.events.lifecycle.StateTransition"

    def __init__(self, *, action: object, msg: Any) -> None:
        self.action = action
        self.msg = msg
        self.timestamp = msg.timestamp
        self.transition = msg.transition.label
        self.start_state = msg.start_state.label
        self.goal_state = msg.goal_state.label


class LifecycleNode(ExecuteNode):
    """A ``<node>`` that is a managed node: needs a name; its transitions become
    StateTransition events and ChangeState events reach it."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        #: The node's full name once the action ran (what ``matches_node_name`` compares).
        self.fqn: str | None = None

    def execute(self, context: LaunchContext) -> None:
        """Follow the node's transitions, serve ChangeState, start the process."""
        if self.node_name is None or not perform(self.node_name, context):
            raise RuntimeLaunchError(
                "a lifecycle node needs a name", self.location, expected="name='...'"
            )
        fqn = self.full_name(context)
        self.fqn = fqn
        link = context.ros()
        if link is not None:
            link.watch_transitions(fqn, lambda msg: self._transition(context, msg))

        def change(event: object, ctx: LaunchContext) -> list[Any]:
            assert isinstance(event, ChangeState)
            if event.lifecycle_node_matcher(self):
                self._request(ctx, event.transition_id)
            return []

        handler = _Callback(lambda event: isinstance(event, ChangeState), change)
        handler.internal = True
        context.register_handler(handler)
        super().execute(context)

    def _transition(self, context: LaunchContext, msg: Any) -> None:
        context.emit(StateTransition(action=self, msg=msg))

    def _request(self, context: LaunchContext, transition_id: int) -> None:
        link = context.ros()
        if link is None:
            context.log("INFO", f"would ask {self.fqn} for {TRANSITIONS[transition_id]}")
            return
        assert self.fqn is not None
        link.change_state(self.fqn, transition_id, context.runner.log)


class _Callback(EventHandler):
    """A handler whose reaction is a function of the event and the context."""

    def __init__(
        self,
        matcher: Callable[[Event], bool],
        react: Callable[[object, LaunchContext], list[Any]],
    ) -> None:
        super().__init__(matcher=matcher)
        self.react = react

    def handle(self, event: object, context: LaunchContext) -> list[Any]:
        """What the function returns."""
        return self.react(event, context)
