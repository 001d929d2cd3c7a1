"""Managed (lifecycle) nodes, shaped like ``rclpy.lifecycle``.

::

    from launchkit.ros.lifecycle import LifecycleNode, State, TransitionCallbackReturn

    class Talker(LifecycleNode):
        def on_configure(self, state: State) -> TransitionCallbackReturn:
            self.pub = self.create_lifecycle_publisher(String, "chatter", 10)
            return TransitionCallbackReturn.SUCCESS

A lifecycle node serves ``~/change_state``, ``~/get_state``, ``~/get_available_states``,
``~/get_available_transitions`` and ``~/get_transition_graph`` and publishes every transition
on ``~/transition_event`` (lifecycle_msgs), as rclpy's does, so ``launch_ros``' LifecycleNode
and ``ros2 lifecycle`` drive it. The states and edges are :mod:`launchkit.ros.lifecycle_machine`.
"""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable
from typing import Any

from launchkit.ros import lifecycle_machine as sm
from launchkit.ros.node import Node
from launchkit.ros.topics import Publisher


class TransitionCallbackReturn(enum.IntEnum):
    """What a transition callback returns (lifecycle_msgs' TRANSITION_CALLBACK_* values)."""

    SUCCESS = sm.CALLBACK_SUCCESS
    FAILURE = sm.CALLBACK_FAILURE
    ERROR = sm.CALLBACK_ERROR


class State:
    """A lifecycle state, as handed to the callbacks (``state_id``, ``label``)."""

    def __init__(self, state_id: int, label: str) -> None:
        self.state_id = state_id
        self.label = label

    def __repr__(self) -> str:
        return f"State(state_id={self.state_id}, label={self.label!r})"


class ManagedEntity:
    """Something a lifecycle node switches on and off with its own transitions."""

    def on_configure(self, state: State) -> TransitionCallbackReturn:
        """Called while configuring."""
        return TransitionCallbackReturn.SUCCESS

    def on_cleanup(self, state: State) -> TransitionCallbackReturn:
        """Called while cleaning up."""
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: State) -> TransitionCallbackReturn:
        """Called while shutting down."""
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        """Called while activating."""
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: State) -> TransitionCallbackReturn:
        """Called while deactivating."""
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state: State) -> TransitionCallbackReturn:
        """Called while processing an error."""
        return TransitionCallbackReturn.SUCCESS


class SimpleManagedEntity(ManagedEntity):
    """A managed entity that is enabled while the node is active."""

    def __init__(self) -> None:
        self._enabled = False

    @property
    def is_activated(self) -> bool:
        """Whether the node is active."""
        return self._enabled

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        """Enable it."""
        self._enabled = True
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: State) -> TransitionCallbackReturn:
        """Disable it."""
        self._enabled = False
        return TransitionCallbackReturn.SUCCESS


class LifecyclePublisher(SimpleManagedEntity):
    """A publisher that publishes only while its node is active (rclpy's)."""

    def __init__(self, publisher: Publisher) -> None:
        super().__init__()
        self.publisher = publisher

    def publish(self, msg: Any) -> None:
        """Publish ``msg`` if the node is active; drop it otherwise."""
        if self._enabled:
            self.publisher.publish(msg)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.publisher, name)


_REQUEST_CALLBACKS = {
    sm.CONFIGURING: "on_configure",
    sm.CLEANINGUP: "on_cleanup",
    sm.ACTIVATING: "on_activate",
    sm.DEACTIVATING: "on_deactivate",
    sm.SHUTTINGDOWN: "on_shutdown",
    sm.ERRORPROCESSING: "on_error",
}


class LifecycleNode(Node):
    """A managed node: starts ``unconfigured``; ``trigger_configure()`` and the ROS services
    move it, calling ``on_configure`` ... ``on_error`` (override them) on the way."""

    def __init__(
        self, node_name: str, *, enable_communication_interface: bool = True, **kwargs: Any
    ) -> None:
        super().__init__(node_name, **kwargs)
        self._state = sm.UNCONFIGURED
        self._transition_lock = threading.RLock()
        self._managed: list[ManagedEntity] = []
        self._callbacks: dict[int, Callable[[State], TransitionCallbackReturn]] = {}
        self._events: Publisher | None = None
        if enable_communication_interface:
            from launchkit.ros.lifecycle_services import serve_lifecycle

            self._events = serve_lifecycle(self)

    # -- the machine ------------------------------------------------------------------------

    @property
    def current_state(self) -> State:
        """The state the node is in."""
        return State(self._state, sm.STATE_LABELS[self._state])

    def change_state(self, transition_id: int, label: str = "") -> bool:
        """Run the request ``transition_id`` (or ``label``) to its end; whether its callback
        succeeded (False when the current state does not accept it)."""
        with self._transition_lock:
            request = sm.request(self._state, transition_id, label)
            if request is None:
                self.get_logger().warning(
                    f"transition {label or transition_id} is not available "
                    f"from state '{sm.STATE_LABELS[self._state]}'"
                )
                return False
            self._enter(request, self._state)
            outcome = self._call(request.goal)
            self._enter(sm.result(request.goal, outcome), request.goal)
            if self._state == sm.ERRORPROCESSING:
                recovery = self._call(sm.ERRORPROCESSING)
                self._enter(sm.result(sm.ERRORPROCESSING, recovery), sm.ERRORPROCESSING)
            return outcome == TransitionCallbackReturn.SUCCESS

    def _enter(self, transition: sm.Transition, start: int) -> None:
        self._state = transition.goal
        if self._events is not None:
            from launchkit.ros.lifecycle_services import transition_event

            self._events.publish(transition_event(transition, start, time.time_ns()))

    def _call(self, transition_state: int) -> int:
        state = State(transition_state, sm.STATE_LABELS[transition_state])
        callback = self._callbacks.get(transition_state) or getattr(
            self, _REQUEST_CALLBACKS[transition_state]
        )
        try:
            outcome = int(callback(state))
        except Exception as error:  # a failing callback is the ERROR outcome, as in rclpy
            self.get_logger().error(f"{callback.__name__} raised {type(error).__name__}: {error}")
            return sm.CALLBACK_ERROR
        if outcome != sm.CALLBACK_SUCCESS:
            return outcome
        for entity in self._managed:
            result = int(getattr(entity, _REQUEST_CALLBACKS[transition_state])(state))
            if result != sm.CALLBACK_SUCCESS:
                return result
        return outcome

    # -- rclpy's API --------------------------------------------------------------------------

    def register_callback(
        self, state_id: int, callback: Callable[[State], TransitionCallbackReturn]
    ) -> bool:
        """Use ``callback`` for transition state ``state_id`` instead of the method."""
        self._callbacks[state_id] = callback
        return True

    def add_managed_entity(self, entity: ManagedEntity) -> None:
        """Switch ``entity`` on and off with the node's transitions."""
        self._managed.append(entity)

    def create_lifecycle_publisher(
        self, msg_type: Any, topic: str, qos_profile: Any, **kwargs: Any
    ) -> LifecyclePublisher:
        """A publisher that only publishes while the node is active."""
        publisher = LifecyclePublisher(self.create_publisher(msg_type, topic, qos_profile))
        if self._state == sm.ACTIVE:
            publisher._enabled = True
        self.add_managed_entity(publisher)
        return publisher

    def trigger_configure(self) -> TransitionCallbackReturn:
        """``configure``."""
        return self._trigger(sm.CONFIGURE)

    def trigger_cleanup(self) -> TransitionCallbackReturn:
        """``cleanup``."""
        return self._trigger(sm.CLEANUP)

    def trigger_activate(self) -> TransitionCallbackReturn:
        """``activate``."""
        return self._trigger(sm.ACTIVATE)

    def trigger_deactivate(self) -> TransitionCallbackReturn:
        """``deactivate``."""
        return self._trigger(sm.DEACTIVATE)

    def trigger_shutdown(self) -> TransitionCallbackReturn:
        """``shutdown`` from whatever primary state the node is in."""
        return self._trigger(sm.UNCONFIGURED_SHUTDOWN)

    def _trigger(self, transition_id: int) -> TransitionCallbackReturn:
        ok = self.change_state(transition_id)
        return TransitionCallbackReturn.SUCCESS if ok else TransitionCallbackReturn.FAILURE

    # the callbacks a subclass overrides (rclpy's defaults: success, but on_error fails)

    def on_configure(self, state: State) -> TransitionCallbackReturn:
        """While configuring."""
        return TransitionCallbackReturn.SUCCESS

    def on_cleanup(self, state: State) -> TransitionCallbackReturn:
        """While cleaning up."""
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        """While activating."""
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: State) -> TransitionCallbackReturn:
        """While deactivating."""
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: State) -> TransitionCallbackReturn:
        """While shutting down."""
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state: State) -> TransitionCallbackReturn:
        """While processing an error (failing: the node is finalized)."""
        return TransitionCallbackReturn.FAILURE


__all__ = [
    "LifecycleNode",
    "LifecyclePublisher",
    "ManagedEntity",
    "SimpleManagedEntity",
    "State",
    "TransitionCallbackReturn",
]
