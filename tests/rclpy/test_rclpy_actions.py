"""rclpy's actions on launchkit: the same node files print the same on the real rclpy (Fast
DDS) and on launchkit's rclpy (Zenoh), and launchkit's action entities sit at rmw_zenoh's keys.

The node files use test_msgs' Fibonacci where the ros-jazzy wheels are installed (the real
rclpy has no example_interfaces there), else example_interfaces' (the same fields).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
import scenarios
from rclpy_runs import LAUNCHKIT, PATIENCE, REAL, Runs, real_rclpy, scenario_output

from launchkit.ros.action import ActionClient, ActionServer, GoalResponse
from launchkit.ros.action.goal_state import GoalEvent, GoalStatus, transition
from launchkit.ros.callback_groups import ReentrantCallbackGroup
from launchkit.ros.context import Context, RCLError
from launchkit.ros.executors import MultiThreadedExecutor
from launchkit.ros.keyexpr import dds_type_name
from launchkit.ros.msgs import get_action, get_message, type_hash
from launchkit.ros.node import Node

FLAVOURS = [LAUNCHKIT, pytest.param(REAL, marks=real_rclpy)]
Make = Callable[[str], Runs]

ACTIONS = """\
== client (status 0)
server ready: True
actions: [('/fibonacci', [True])]
order 5: accepted True
feedback: [0, 1, 1]
feedback: [0, 1, 1, 2]
feedback: [0, 1, 1, 2, 3]
feedback: [0, 1, 1, 2, 3, 5]
result: status 4 sequence [0, 1, 1, 2, 3, 5]
goal handle status: 4
order -1: accepted False
cancel: return code 0, canceling this goal [True]
result: status 5 sequence [0, 1]
order 13: status 6 sequence []
cancel an ended goal: return code 3
-- stderr
== server (status 0)
serving
-- stderr
[INFO] [T] [fibonacci_server]: goal request: order 5
[INFO] [T] [fibonacci_server]: executing: order 5, status 2
[INFO] [T] [fibonacci_server]: succeeded: [0, 1, 1, 2, 3, 5]
[INFO] [T] [fibonacci_server]: goal request: order -1
[INFO] [T] [fibonacci_server]: goal request: order 1000
[INFO] [T] [fibonacci_server]: executing: order 1000, status 2
[INFO] [T] [fibonacci_server]: cancel request: order 1000
[INFO] [T] [fibonacci_server]: canceled: status 5
[INFO] [T] [fibonacci_server]: goal request: order 13
[INFO] [T] [fibonacci_server]: executing: order 13, status 2
[INFO] [T] [fibonacci_server]: aborted: active False
"""

TWO_CLIENTS = """\
== racer 6 (status 0)
order 6: feedback of other goals 0
order 6: result [0, 1, 1, 2, 3, 5, 8]
-- stderr
== racer 9 (status 0)
order 9: feedback of other goals 0
order 9: result [0, 1, 1, 2, 3, 5, 8, 13, 21, 34]
-- stderr
server status 0
"""


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_goals_with_feedback_cancel_and_abort(runs: Make, flavour: str) -> None:
    assert scenario_output(runs, flavour, scenarios.actions) == ACTIONS


@pytest.mark.parametrize("flavour", FLAVOURS)
def test_two_clients_follow_their_own_goals(runs: Make, flavour: str) -> None:
    assert scenario_output(runs, flavour, scenarios.two_action_clients) == TWO_CLIENTS


# launchkit's side, in this process ----------------------------------------------------------
FIBONACCI = "example_interfaces/action/Fibonacci"


@pytest.fixture
def spinning(router: str) -> Iterator[Node]:
    """A node of a context of its own, spun by a MultiThreadedExecutor in a thread."""
    context = Context()
    context.init([])
    node = Node("action_test", context=context)
    executor = MultiThreadedExecutor(num_threads=4, context=context)
    executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    try:
        yield node
    finally:
        executor.shutdown()
        context.try_shutdown()
        thread.join(PATIENCE)


def _succeed(goal_handle: Any) -> Any:
    goal_handle.succeed()
    return get_action(FIBONACCI).Result(sequence=[goal_handle.request.order])


def test_action_entities_have_rmw_zenohs_names_types_and_keys(spinning: Node) -> None:
    action = get_action(FIBONACCI)
    ActionServer(spinning, action, "fibonacci", _succeed)
    ActionClient(spinning, action, "fibonacci")
    graph = spinning.context.graph
    expected = {
        ("SS", "/fibonacci/_action/send_goal", f"{FIBONACCI}_SendGoal"),
        ("SS", "/fibonacci/_action/cancel_goal", "action_msgs/srv/CancelGoal"),
        ("SS", "/fibonacci/_action/get_result", f"{FIBONACCI}_GetResult"),
        ("MP", "/fibonacci/_action/feedback", f"{FIBONACCI}_FeedbackMessage"),
        ("MP", "/fibonacci/_action/status", "action_msgs/msg/GoalStatusArray"),
        ("SC", "/fibonacci/_action/send_goal", f"{FIBONACCI}_SendGoal"),
        ("SC", "/fibonacci/_action/cancel_goal", "action_msgs/srv/CancelGoal"),
        ("SC", "/fibonacci/_action/get_result", f"{FIBONACCI}_GetResult"),
        ("MS", "/fibonacci/_action/feedback", f"{FIBONACCI}_FeedbackMessage"),
        ("MS", "/fibonacci/_action/status", "action_msgs/msg/GoalStatusArray"),
    }

    def announced() -> set[tuple[str, str, str]]:
        return {
            (t.kind, t.topic, t.type_name)
            for t in graph.tokens()
            if t.kind != "NN" and "/_action/" in t.topic
        }

    assert graph.wait_for(lambda: announced() == expected, PATIENCE), announced()
    for token in graph.tokens():
        if "/_action/" in token.topic:
            assert token.type_hash == type_hash(token.type_name)
            # the type as rmw_zenoh writes it in keys: pkg::action::dds_::Fibonacci_SendGoal_
            assert f"/{dds_type_name(token.type_name)}/{token.type_hash}/" in token.key
    status = graph.tokens("MP", "/fibonacci/_action/status")[0].qos
    assert status is not None and (status.durability, status.depth) == (1, 1)  # transient local


def test_results_are_forgotten_after_the_result_timeout(spinning: Node) -> None:
    action = get_action(FIBONACCI)
    server = ActionServer(spinning, action, "fibonacci", _succeed, result_timeout=0.2)
    client = ActionClient(spinning, action, "fibonacci")
    assert client.wait_for_server(PATIENCE)
    sent = client.send_goal_async(action.Goal(order=3))
    assert sent.wait(PATIENCE)
    goal_handle = sent.result()
    first = goal_handle.get_result()
    assert (first.status, list(first.result.sequence)) == (GoalStatus.STATUS_SUCCEEDED, [3])
    deadline = time.monotonic() + PATIENCE
    while goal_handle.get_result().status != GoalStatus.STATUS_UNKNOWN:
        assert time.monotonic() < deadline, "the result was never forgotten"
    assert server._goal_handles == {}


def test_a_goal_callback_that_answers_no_response_rejects(spinning: Node) -> None:
    action = get_action(FIBONACCI)
    ActionServer(spinning, action, "fibonacci", _succeed, goal_callback=lambda goal: True)
    client = ActionClient(spinning, action, "fibonacci")
    assert client.wait_for_server(PATIENCE)
    sent = client.send_goal_async(action.Goal(order=1))
    assert sent.wait(PATIENCE)
    assert not sent.result().accepted  # True is not GoalResponse.ACCEPT, as in rclpy


def test_goal_transitions_are_rcl_actions() -> None:
    assert transition(GoalStatus.STATUS_ACCEPTED, GoalEvent.EXECUTE) == 2
    assert transition(GoalStatus.STATUS_EXECUTING, GoalEvent.CANCEL_GOAL) == 3
    assert transition(GoalStatus.STATUS_CANCELING, GoalEvent.SUCCEED) == 4
    with pytest.raises(RCLError, match="invalid transition from state ACCEPTED with event SUCCEED"):
        transition(GoalStatus.STATUS_ACCEPTED, GoalEvent.SUCCEED)
    with pytest.raises(RCLError):
        transition(GoalStatus.STATUS_SUCCEEDED, GoalEvent.ABORT)


def test_feedback_that_overtakes_the_goal_response_comes_after_it(spinning: Node) -> None:
    # Zenoh may bring a goal's first feedback before the response accepting it (another key,
    # another thread): the goal callback below publishes feedback for the goal and accepts only
    # once that feedback is in the client's process, so it always arrives first here
    action = get_action(FIBONACCI)
    goal_id = get_message("unique_identifier_msgs/msg/UUID")(uuid=list(range(16)))
    arrived = threading.Event()
    spinning.create_subscription(
        action.Impl.FeedbackMessage,
        "/fibonacci/_action/feedback",
        lambda _: arrived.set(),
        10,
        callback_group=ReentrantCallbackGroup(),
    )
    early = spinning.create_publisher(
        action.Impl.FeedbackMessage, "/fibonacci/_action/feedback", 10
    )

    def accept_after_feedback(goal: Any) -> GoalResponse:
        early.publish(action.Impl.FeedbackMessage(goal_id=goal_id))
        assert arrived.wait(PATIENCE), "the early feedback never came"
        return GoalResponse.ACCEPT

    ActionServer(
        spinning,
        action,
        "fibonacci",
        _succeed,
        goal_callback=accept_after_feedback,
        callback_group=ReentrantCallbackGroup(),
    )
    client = ActionClient(spinning, action, "fibonacci")
    assert client.wait_for_server(PATIENCE)
    events: list[str] = []
    sent = client.send_goal_async(
        action.Goal(order=2), lambda _: events.append("feedback"), goal_uuid=goal_id
    )
    sent.add_done_callback(lambda _: events.append("accepted"))
    assert sent.wait(PATIENCE)
    result = sent.result().get_result_async()  # the goal ends before the executor does
    assert result.wait(PATIENCE) and result.result().status == GoalStatus.STATUS_SUCCEEDED
    deadline = time.monotonic() + PATIENCE
    while len(events) < 2:
        assert time.monotonic() < deadline, events
        time.sleep(0.01)
    assert events == ["accepted", "feedback"]
