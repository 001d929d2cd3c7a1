"""Actions through ``launchkit bridge``: a real rclpy ActionClient reaches a launchkit
ActionServer, and a launchkit ActionClient a real rclpy ActionServer (their services and topics
bridged like any other).

test_msgs' Fibonacci on both sides: the wheels have no example_interfaces, and launchkit reads
test_msgs from its interface files in the wheels' ``share/`` (``AMENT_PREFIX_PATH``). So the
launchkit side runs as processes with that environment: the rclpy tests' node files on
launchkit's rclpy (``tests/rclpy/nodes``), and the bridge.
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Iterator
from typing import Any

import pytest
from bridge_helpers import BridgeProcess, DdsPeer, wait_until

from tests.rclpy.rclpy_runs import LAUNCHKIT, NodeRun, environment

pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

WAIT = 30.0


@pytest.fixture(scope="module")
def bridge(router: str, dds_domain: int) -> Iterator[BridgeProcess]:
    """``launchkit bridge`` that knows test_msgs (the wheels' prefix on AMENT_PREFIX_PATH)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("AMENT_PREFIX_PATH", sys.prefix)
        process = BridgeProcess(router, dds_domain)
    process.wait_line("bridging ROS_DOMAIN_ID")
    yield process
    assert process.stop() == 0, "\n".join(process.lines[-30:])


@pytest.fixture
def launchkit_node(router: str, dds_domain: int) -> Iterator[Any]:
    """``launchkit_node(FILE, *args)``: a node file of tests/rclpy/nodes on launchkit's rclpy."""
    started: list[NodeRun] = []

    def start(name: str, *args: str) -> NodeRun:
        started.append(NodeRun(name, environment(LAUNCHKIT, router, dds_domain), args))
        return started[-1]

    yield start
    for run in started:
        run.kill()


def test_an_rclpy_action_client_reaches_a_launchkit_server(
    bridge: BridgeProcess, dds: DdsPeer, launchkit_node: Any
) -> None:
    from rclpy.action import ActionClient
    from test_msgs.action import Fibonacci

    server = launchkit_node("fibonacci_server.py")
    server.expect("serving")
    client = ActionClient(dds.node, Fibonacci, "/fibonacci")
    assert client.wait_for_server(timeout_sec=WAIT), "the action server never appeared"
    feedback: list[list[int]] = []
    sent = client.send_goal_async(
        Fibonacci.Goal(order=4),
        feedback_callback=lambda m: feedback.append(list(m.feedback.sequence)),
    )
    wait_until(sent.done, WAIT, "the goal's answer")
    assert sent.result().accepted
    result = sent.result().get_result_async()
    wait_until(result.done, WAIT, "the goal's result")
    assert result.result().status == 4  # SUCCEEDED
    assert list(result.result().result.sequence) == [0, 1, 1, 2, 3]
    assert feedback  # some feedback came through (the first may race the subscription)
    client.destroy()
    status, _, err = server.finish(signal.SIGINT)
    assert status == 0, err
    assert "goal request: order 4" in err and "succeeded: [0, 1, 1, 2, 3]" in err


def test_a_launchkit_action_client_reaches_an_rclpy_server(
    bridge: BridgeProcess, dds: DdsPeer, launchkit_node: Any
) -> None:
    from rclpy.action import ActionServer
    from test_msgs.action import Fibonacci

    def execute(goal_handle: Any) -> Any:
        sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            sequence.append(sequence[i] + sequence[i - 1])
            goal_handle.publish_feedback(Fibonacci.Feedback(sequence=sequence))
        goal_handle.succeed()
        return Fibonacci.Result(sequence=sequence)

    server = ActionServer(dds.node, Fibonacci, "/fibonacci", execute)
    try:
        racer = launchkit_node("fibonacci_racer.py", "4")
        status, out, err = racer.finish()
    finally:
        server.destroy()
    assert status == 0, err
    assert out == "order 4: feedback of other goals 0\norder 4: result [0, 1, 1, 2, 3]\n"
