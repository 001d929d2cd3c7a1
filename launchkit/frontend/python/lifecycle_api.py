"""Stand-ins for launch_ros's lifecycle API: ``LifecycleNode``, ``LifecycleTransition``, the
``ChangeState`` / ``StateTransition`` events, ``OnStateTransition``, ``matches_node_name``,
and the constants of ``lifecycle_msgs.msg`` that launch files import."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from launchkit.description.actions.base import Action
from launchkit.description.actions.lifecycle import ChangeState, StateTransition
from launchkit.description.actions.lifecycle import LifecycleNode as LifecycleNodeAction
from launchkit.description.conditions import Condition
from launchkit.description.events import Event
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions.base import perform
from launchkit.errors import LaunchFileError, RuntimeLaunchError
from launchkit.frontend.python.event_api import _Reaction
from launchkit.frontend.python.ros_api import node_arguments
from launchkit.frontend.python.values import here, to_value


class State:
    """``lifecycle_msgs.msg.State``'s constants."""

    PRIMARY_STATE_UNKNOWN = 0
    PRIMARY_STATE_UNCONFIGURED = 1
    PRIMARY_STATE_INACTIVE = 2
    PRIMARY_STATE_ACTIVE = 3
    PRIMARY_STATE_FINALIZED = 4
    TRANSITION_STATE_CONFIGURING = 10
    TRANSITION_STATE_CLEANINGUP = 11
    TRANSITION_STATE_SHUTTINGDOWN = 12
    TRANSITION_STATE_ACTIVATING = 13
    TRANSITION_STATE_DEACTIVATING = 14
    TRANSITION_STATE_ERRORPROCESSING = 15


class Transition:
    """``lifecycle_msgs.msg.Transition``'s constants (the requests)."""

    TRANSITION_CREATE = 0
    TRANSITION_CONFIGURE = 1
    TRANSITION_CLEANUP = 2
    TRANSITION_ACTIVATE = 3
    TRANSITION_DEACTIVATE = 4
    TRANSITION_UNCONFIGURED_SHUTDOWN = 5
    TRANSITION_INACTIVE_SHUTDOWN = 6
    TRANSITION_ACTIVE_SHUTDOWN = 7
    TRANSITION_DESTROY = 8


class LifecycleNode(LifecycleNodeAction):
    """``launch_ros.actions.LifecycleNode(name=..., namespace=..., ...)``."""

    def __init__(self, *, name: Any, namespace: Any = "", **kwargs: Any) -> None:
        arguments = node_arguments(name=name, namespace=namespace, **kwargs)
        super().__init__(
            arguments.pop("pkg"), arguments.pop("exec"), arguments.pop("options"), **arguments
        )


def matches_node_name(node_name: str) -> Callable[[Any], bool]:
    """``launch_ros.events.matches_node_name``: the lifecycle node with that full name."""
    wanted = node_name if node_name.startswith("/") else "/" + node_name
    return lambda action: getattr(action, "fqn", None) == wanted


def ChangeStateEvent(*, lifecycle_node_matcher: Callable[[Any], bool], transition_id: int) -> Event:
    """``launch_ros.events.lifecycle.ChangeState``: an unknown transition id is an error at
    the line that builds it."""
    try:
        return ChangeState(
            lifecycle_node_matcher=lifecycle_node_matcher, transition_id=transition_id
        )
    except ValueError as error:
        raise LaunchFileError(
            str(error), here(), expected="a lifecycle_msgs Transition id"
        ) from None


class OnStateTransition(_Reaction):
    """``launch_ros.event_handlers.OnStateTransition``: StateTransition events of one lifecycle
    node (or any), filtered by transition, start and goal state labels (or ``matcher``)."""

    def __init__(
        self,
        *,
        entities: Any,
        target_lifecycle_node: Any = None,
        transition: str | None = None,
        start_state: str | None = None,
        goal_state: str | None = None,
        matcher: Callable[[Event], bool] | None = None,
        handle_once: bool = False,
    ) -> None:
        def matches(event: Event) -> bool:
            return (
                isinstance(event, StateTransition)
                and (target_lifecycle_node is None or event.action is target_lifecycle_node)
                and (transition is None or event.transition == transition)
                and (start_state is None or event.start_state == start_state)
                and (goal_state is None or event.goal_state == goal_state)
            )

        super().__init__(matcher or matches, entities, "OnStateTransition", handle_once)
        self.goal = goal_state

    def describe(self) -> str:
        """What it waits for."""
        return f"OnStateTransition(goal_state={self.goal})" if self.goal else "OnStateTransition"


#: Where each request leads (the state labels of the transition that completes it).
_TARGETS = {
    1: ("configuring", "inactive"),
    2: ("cleaningup", "unconfigured"),
    3: ("activating", "active"),
    4: ("deactivating", "inactive"),
    5: ("shuttingdown", "finalized"),
    6: ("shuttingdown", "finalized"),
    7: ("shuttingdown", "finalized"),
}


class LifecycleTransition(Action):
    """``launch_ros.actions.LifecycleTransition``: make the named lifecycle nodes go through
    ``transition_ids`` in order, each after the previous one completed."""

    def __init__(
        self,
        *,
        lifecycle_node_names: Iterable[Any],
        transition_ids: Iterable[Any],
        condition: Condition | None = None,
    ) -> None:
        super().__init__(here(), condition)
        self.names = [to_value(name) for name in lifecycle_node_names]
        self.ids = [to_value(str(i) if isinstance(i, int) else i) for i in transition_ids]
        if not self.names or not self.ids:
            raise LaunchFileError(
                "LifecycleTransition needs node names and transition ids",
                self.location,
                expected="lifecycle_node_names=[...], transition_ids=[...]",
            )

    def execute(self, context: LaunchContext) -> None:
        """Emit the first request for each node; each completion emits the next."""
        ids = []
        for value in self.ids:
            text = perform(value, context)
            if not text.isdigit() or int(text) not in _TARGETS:
                raise RuntimeLaunchError(
                    f"lifecycle transition {text!r}",
                    self.location,
                    expected="a request id of lifecycle_msgs Transition (1 to 7)",
                )
            ids.append(int(text))
        for name in (perform(value, context) for value in self.names):
            changes = [
                ChangeState(lifecycle_node_matcher=matches_node_name(name), transition_id=i)
                for i in ids
            ]
            for index, transition_id in enumerate(ids[:-1]):
                start, goal = _TARGETS[transition_id]
                after = _NextRequest(matches_node_name(name), start, goal, changes[index + 1])
                context.register_handler(after)
            context.emit(changes[0])


class _NextRequest(_Reaction):
    """Once the node's transition reaches ``goal`` from ``start``, emit ``change`` (once)."""

    def __init__(
        self, node: Callable[[Any], bool], start: str, goal: str, change: ChangeState
    ) -> None:
        def matches(event: Event) -> bool:
            return (
                isinstance(event, StateTransition)
                and node(event.action)
                and event.start_state == start
                and event.goal_state == goal
            )

        super().__init__(matches, [], "LifecycleTransition", handle_once=True)
        self.change = change
        self.internal = True

    def handle(self, event: object, context: LaunchContext) -> list[Any]:
        """Emit the next request."""
        context.emit(self.change)
        return []


__all__ = [
    "ChangeStateEvent",
    "LifecycleNode",
    "LifecycleTransition",
    "OnStateTransition",
    "State",
    "StateTransition",
    "Transition",
    "matches_node_name",
]
