"""``launchkit action list|info|send_goal`` against an rclpy action server running on
launchkit's rclpy (``nodes/fibonacci_server.py``), printing what ``ros2 action`` prints."""

from __future__ import annotations

import re
import select
import signal
import subprocess
import sys
import time
from collections.abc import Callable

from rclpy_runs import LAUNCHKIT, PATIENCE, NodeRun, Runs

Make = Callable[[str], Runs]


def action(runs: Runs, *args: str) -> str:
    """``launchkit action ARGS`` in the runs' environment: its output (status 0 required)."""
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "action", *args],
        env=runs.env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def serving(runs: Runs) -> NodeRun:
    """The Fibonacci server, up (its node files pick the Fibonacci type; see fibonacci_type)."""
    server = runs.start("fibonacci_server.py")
    server.expect("serving")
    return server


def test_list_and_info(runs: Make) -> None:
    made = runs(LAUNCHKIT)
    server = serving(made)
    kind = action(made, "list", "-t").split(" [")[1]
    assert kind.endswith("/action/Fibonacci]\n")
    assert action(made, "list") == "/fibonacci\n"
    assert action(made, "list", "-c") == "1\n"
    assert action(made, "info", "/fibonacci") == (
        "Action: /fibonacci\nAction clients: 0\nAction servers: 1\n    /fibonacci_server\n"
    )
    assert action(made, "info", "fibonacci", "-t") == (
        f"Action: fibonacci\nAction clients: 0\nAction servers: 1\n    /fibonacci_server [{kind}"
    )
    assert action(made, "info", "/elsewhere", "-c") == (
        "Action: /elsewhere\nAction clients: 0\nAction servers: 0\n"
    )
    server.finish(signal.SIGINT)


def _type(runs: Runs) -> str:
    return action(runs, "list", "-t").split(" [")[1].rstrip("]\n")


def test_send_goal_with_feedback(runs: Make) -> None:
    made = runs(LAUNCHKIT)
    server = serving(made)
    out = action(made, "send_goal", "--feedback", "/fibonacci", _type(made), "{order: 3}")
    out = re.sub(r"ID: [0-9a-f]{32}", "ID: X", out)
    assert out == (
        "Waiting for an action server to become available...\n"
        "Sending goal:\n     order: 3\n\n"
        "Goal accepted with ID: X\n\n"
        "Feedback:\n    sequence:\n- 0\n- 1\n- 1\n\n"
        "Feedback:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n\n"
        "Result:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n\n"
        "Goal finished with status: SUCCEEDED\n"
    )
    assert action(made, "send_goal", "/fibonacci", _type(made), "{order: -1}").endswith(
        "Goal was rejected.\n"
    )
    assert action(made, "send_goal", "/fibonacci", _type(made), "order: 13").endswith(
        "Goal finished with status: ABORTED\n"
    )
    server.finish(signal.SIGINT)


def test_a_stopped_send_goal_cancels_its_goal(runs: Make) -> None:
    made = runs(LAUNCHKIT)
    server = serving(made)
    command = ["action", "send_goal", "/fibonacci", _type(made), "{order: 1000}"]
    sender = subprocess.Popen(
        [sys.executable, "-m", "launchkit", *command],
        env=made.env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        _wait_for_line(sender, "Goal accepted")
        server.expect("executing: order 1000")
        sender.send_signal(signal.SIGTERM)
        out, err = sender.communicate(timeout=120)
    finally:
        if sender.poll() is None:
            sender.kill()
            sender.wait()
    assert sender.returncode == 0, err
    assert out.endswith("Canceling goal...\nGoal canceled.\n"), out
    server.expect("canceled: status 5")
    server.finish(signal.SIGINT)


def _wait_for_line(process: subprocess.Popen[str], text: str) -> None:
    """Read ``process``'s stdout until a line contains ``text`` (within the patience)."""
    assert process.stdout is not None
    deadline = time.monotonic() + PATIENCE
    seen = []
    while time.monotonic() < deadline:
        ready, _, _ = select.select([process.stdout], [], [], deadline - time.monotonic())
        line = process.stdout.readline() if ready else ""
        seen.append(line)
        if text in line:
            return
        if not line and process.poll() is not None:
            break
    raise AssertionError(f"no line with {text!r}; so far: {seen}")


def test_an_unknown_action_type_is_a_usage_error(runs: Make) -> None:
    made = runs(LAUNCHKIT)
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "action", "send_goal", "/f", "nope/action/Nope"],
        env=made.env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2
    assert done.stderr.startswith("error: unknown action type 'nope/action/Nope'"), done.stderr
