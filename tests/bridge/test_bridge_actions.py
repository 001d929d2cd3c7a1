"""Actions through ``launchkit bridge``: a real rclpy ActionClient reaches a launchkit
ActionServer, and a launchkit ActionClient a real rclpy ActionServer (their services and topics
bridged like any other). test_msgs' Fibonacci on both sides: the wheels have no
example_interfaces, and launchkit reads test_msgs from its interface files in the wheels'
``share/`` (``AMENT_PREFIX_PATH``)."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from typing import Any

import pytest
from bridge_helpers import BridgeProcess, DdsPeer, LaunchkitPeer, wait_until

from launchkit.ros.action import ActionClient, ActionServer
from launchkit.ros.msgs import get_action

pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

WAIT = 30.0
FIBONACCI = "test_msgs/action/Fibonacci"


@pytest.fixture(scope="module")
def ament(dds_domain: int) -> Iterator[None]:
    """The wheels' prefix on ``AMENT_PREFIX_PATH``: launchkit finds test_msgs there."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("AMENT_PREFIX_PATH", sys.prefix)
        yield


@pytest.fixture(scope="module")
def bridge(ament: None, router: str, dds_domain: int) -> Iterator[BridgeProcess]:
    """``launchkit bridge`` that knows test_msgs."""
    process = BridgeProcess(router, dds_domain)
    process.wait_line("bridging ROS_DOMAIN_ID")
    yield process
    assert process.stop() == 0, "\n".join(process.lines[-30:])


@pytest.fixture(scope="module")
def lk(ament: None, router: str, dds_domain: int) -> Iterator[LaunchkitPeer]:
    """A launchkit node on the module's router."""
    peer = LaunchkitPeer(router, dds_domain)
    yield peer
    peer.close()


def _execute(goal_handle: Any, result_type: Any, feedback_type: Any) -> Any:
    sequence = [0, 1]
    for i in range(1, goal_handle.request.order):
        sequence.append(sequence[i] + sequence[i - 1])
        goal_handle.publish_feedback(feedback_type(sequence=sequence))
    goal_handle.succeed()
    return result_type(sequence=sequence)


def _follow(client: Any, goal: Any) -> tuple[list[list[int]], Any]:
    """Send ``goal`` from the test thread (the peer spins elsewhere): feedback and result."""
    assert client.wait_for_server(timeout_sec=WAIT), "the action server never appeared"
    feedback: list[list[int]] = []
    sent = client.send_goal_async(
        goal, feedback_callback=lambda m: feedback.append(list(m.feedback.sequence))
    )
    wait_until(sent.done, WAIT, "the goal's answer")
    goal_handle = sent.result()
    assert goal_handle.accepted
    result = goal_handle.get_result_async()
    wait_until(result.done, WAIT, "the goal's result")
    return feedback, result.result()


def test_an_rclpy_action_client_reaches_a_launchkit_server(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rclpy.action import ActionClient as RclpyActionClient
    from test_msgs.action import Fibonacci as RclpyFibonacci

    fibonacci = get_action(FIBONACCI)
    ActionServer(
        lk.node,
        fibonacci,
        "/lk_fibonacci",
        lambda handle: _execute(handle, fibonacci.Result, fibonacci.Feedback),
    )
    client = RclpyActionClient(dds.node, RclpyFibonacci, "/lk_fibonacci")
    feedback, response = _follow(client, RclpyFibonacci.Goal(order=4))
    assert response.status == 4  # SUCCEEDED
    assert list(response.result.sequence) == [0, 1, 1, 2, 3]
    assert feedback[-1:] == [[0, 1, 1, 2, 3]]  # the last, at least (the first may race)


def test_a_launchkit_action_client_reaches_an_rclpy_server(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rclpy.action import ActionServer as RclpyActionServer
    from test_msgs.action import Fibonacci as RclpyFibonacci

    RclpyActionServer(
        dds.node,
        RclpyFibonacci,
        "/dds_fibonacci",
        lambda handle: _execute(handle, RclpyFibonacci.Result, RclpyFibonacci.Feedback),
    )
    fibonacci = get_action(FIBONACCI)
    client = ActionClient(lk.node, fibonacci, "/dds_fibonacci")
    feedback, response = _follow(client, fibonacci.Goal(order=4))
    assert response.status == 4
    assert list(response.result.sequence) == [0, 1, 1, 2, 3]
    assert feedback[-1:] == [[0, 1, 1, 2, 3]]
