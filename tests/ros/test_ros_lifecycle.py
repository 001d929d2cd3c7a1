"""Lifecycle nodes: rcl_lifecycle's state machine, driven over the ROS services and reported
on ``~/transition_event``, with rclpy.lifecycle's Python API."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from launchkit.ros.msgs.lifecycle_msgs.msg import TransitionEvent
from launchkit.ros.msgs.lifecycle_msgs.srv import (
    ChangeState,
    GetAvailableStates,
    GetAvailableTransitions,
    GetState,
)
from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import Node, spin_once
from launchkit.ros.context import Context
from launchkit.ros.lifecycle import LifecycleNode, State, TransitionCallbackReturn


class Talker(LifecycleNode):
    """Configures a lifecycle publisher; fails to activate once when told to."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__("lc_talker", **kwargs)
        self.calls: list[str] = []
        self.fail_next_activation = False
        self.publisher: Any = None

    def on_configure(self, state: State) -> TransitionCallbackReturn:
        self.calls.append(f"configure from {state.label}")
        self.publisher = self.create_lifecycle_publisher(String, "lifecycle_chatter", 10)
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        self.calls.append("activate")
        if self.fail_next_activation:
            self.fail_next_activation = False
            raise RuntimeError("no hardware")
        return super().on_activate(state)

    def on_error(self, state: State) -> TransitionCallbackReturn:
        self.calls.append(f"error in {state.label}")
        return TransitionCallbackReturn.SUCCESS  # recover: back to unconfigured


@pytest.fixture
def served(contexts: Callable[[], Context]) -> Iterator[tuple[Talker, Node]]:
    """The talker spinning in a thread of its own context, and a client node."""
    talker = Talker(context=contexts())
    stop = threading.Event()

    def spin() -> None:
        while not stop.is_set():
            spin_once(talker, timeout_sec=0.05)

    thread = threading.Thread(target=spin, daemon=True)
    thread.start()
    try:
        yield talker, Node("manager", context=contexts())
    finally:
        stop.set()
        thread.join(timeout=5)


def test_transitions_over_the_services(served: tuple[Talker, Node]) -> None:
    talker, manager = served
    events: list[tuple[str, str, str]] = []
    heard: list[str] = []
    manager.create_subscription(
        TransitionEvent,
        "/lc_talker/transition_event",
        lambda m: events.append((m.transition.label, m.start_state.label, m.goal_state.label)),
        10,
    )
    manager.create_subscription(String, "/lifecycle_chatter", lambda m: heard.append(m.data), 10)
    change = manager.create_client(ChangeState, "/lc_talker/change_state")
    get_state = manager.create_client(GetState, "/lc_talker/get_state")
    transitions = manager.create_client(
        GetAvailableTransitions, "/lc_talker/get_available_transitions"
    )
    assert change.wait_for_service(timeout_sec=10) and get_state.wait_for_service(timeout_sec=10)

    def request(transition_id: int) -> bool:
        req = ChangeState.Request()
        req.transition.id = transition_id
        return bool(change.call(req, timeout_sec=10).success)

    assert get_state.call(GetState.Request(), timeout_sec=10).current_state.label == "unconfigured"
    available = transitions.call(GetAvailableTransitions.Request(), timeout_sec=10)
    labels = {t.transition.label for t in available.available_transitions}
    assert labels == {"configure", "unconfigured_shutdown"}
    assert request(3) is False  # activate is not available from unconfigured
    assert request(1) is True
    assert talker.calls == ["configure from configuring"]
    talker.publisher.publish(String(data="too early"))  # inactive: dropped
    assert request(3) is True
    spin_until(manager, lambda: len(events) >= 4, 10, "four transition events")
    assert events[:4] == [
        ("configure", "unconfigured", "configuring"),
        ("configure_success", "configuring", "inactive"),
        ("activate", "inactive", "activating"),
        ("activate_success", "activating", "active"),
    ]
    talker.publisher.publish(String(data="live"))
    spin_until(manager, lambda: heard == ["live"], 10, "the active publisher's message")
    assert get_state.call(GetState.Request(), timeout_sec=10).current_state.id == 3


def test_a_failing_callback_goes_through_errorprocessing(served: tuple[Talker, Node]) -> None:
    talker, manager = served
    talker.fail_next_activation = True
    assert talker.trigger_configure() == TransitionCallbackReturn.SUCCESS
    assert talker.trigger_activate() == TransitionCallbackReturn.FAILURE
    assert talker.calls[-1] == "error in errorprocessing"
    assert talker.current_state.label == "unconfigured"  # on_error succeeded: recovered
    states = manager.create_client(GetAvailableStates, "/lc_talker/get_available_states")
    assert states.wait_for_service(timeout_sec=10)
    answer = states.call(GetAvailableStates.Request(), timeout_sec=10)
    assert len(answer.available_states) == 11
    assert talker.trigger_shutdown() == TransitionCallbackReturn.SUCCESS
    assert talker.current_state.label == "finalized"
