"""turtlesim_node's ``rotate_absolute`` action, as Jazzy's turtle serves it: feedback
``remaining`` while the turtle turns at 1 rad/s, the result ``delta``, cancel, and a new goal or a
velocity command aborting the goal being turned for, with Jazzy's log lines."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from launchkit.ros.msgs.turtlesim.action import RotateAbsolute
from launchkit.ros.msgs.turtlesim.srv import Kill, Spawn

from launchkit.ros.action import ActionClient, GoalStatus
from tests.turtlesim.conftest import DEADLINE, NODE, Program, call, python, spin_until
from tests.turtlesim.test_turtlesim_node import drive


@pytest.fixture(scope="module")
def sim(programs: Callable[..., Program]) -> Program:
    """One turtlesim_node for the module."""
    program = programs(*python(NODE, "--no-viewer"))
    program.wait_log("Spawning turtle [turtle1]")
    return program


@pytest.fixture
def turtle(sim: Program, probe: Any) -> Iterator[str]:
    """A new turtle for one test, heading 0 (a turtle of its own: no server of an earlier
    turtle of the same name can still be in the graph)."""
    name = call(probe, Spawn, "/spawn", x=5.5, y=5.5, theta=0.0, name="").name
    assert name
    yield name
    call(probe, Kill, "/kill", name=name)


@pytest.fixture
def rotate(turtle: str, probe: Any) -> Iterator[ActionClient]:
    """A client of the turtle's rotate_absolute."""
    client = ActionClient(probe, RotateAbsolute, f"/{turtle}/rotate_absolute")
    assert client.wait_for_server(DEADLINE), f"no /{turtle}/rotate_absolute server"
    yield client
    client.destroy()


class Goal:
    """A goal sent by the probe: its handle, the feedback it got, its result."""

    def __init__(self, probe: Any, client: ActionClient, theta: float) -> None:
        self.probe = probe
        self.remaining: list[float] = []
        sent = client.send_goal_async(
            RotateAbsolute.Goal(theta=theta),
            feedback_callback=lambda m: self.remaining.append(m.feedback.remaining),
        )
        spin_until(probe, sent.done, f"the answer to a goal of {theta}")
        self.handle = sent.result()
        assert self.handle.accepted
        self.result = self.handle.get_result_async()

    def feedback(self, count: int = 1) -> None:
        spin_until(self.probe, lambda: len(self.remaining) >= count, f"{count} feedback")

    def end(self) -> Any:
        spin_until(self.probe, self.result.done, "the goal's result")
        return self.result.result()


def test_a_goal_turns_the_turtle_with_feedback(sim: Program, probe: Any, rotate: Any) -> None:
    mark = sim.mark()
    goal = Goal(probe, rotate, math.pi / 2)
    response = goal.end()
    assert response.status == GoalStatus.STATUS_SUCCEEDED
    assert response.result.delta == pytest.approx(-math.pi / 2, abs=0.05)
    assert goal.remaining[0] == pytest.approx(math.pi / 2, abs=0.05)
    assert goal.remaining == sorted(goal.remaining, reverse=True)
    assert len(goal.remaining) > 50  # 1.57 s of 16 ms steps
    # the log line may come after the result: the node's stderr is read as it comes
    assert sim.wait_log("Rotation goal completed successfully", mark).startswith("[INFO]")


def test_a_goal_is_canceled(sim: Program, probe: Any, rotate: Any) -> None:
    mark = sim.mark()
    goal = Goal(probe, rotate, 2.5)
    goal.feedback(3)
    canceling = goal.handle.cancel_goal_async()
    spin_until(probe, canceling.done, "the cancel answer")
    assert len(canceling.result().goals_canceling) == 1
    response = goal.end()
    assert response.status == GoalStatus.STATUS_CANCELED
    assert -2.5 < response.result.delta < 0.0
    sim.wait_log("Rotation goal canceled", mark)


def test_a_new_goal_aborts_the_previous_one(sim: Program, probe: Any, rotate: Any) -> None:
    mark = sim.mark()
    first = Goal(probe, rotate, 2.5)
    first.feedback(3)
    second = Goal(probe, rotate, -math.pi / 4)
    assert first.end().status == GoalStatus.STATUS_ABORTED
    aborted = "Rotation goal received before a previous goal finished. Aborting previous goal"
    assert sim.wait_log(aborted, mark).startswith("[WARN]")
    assert second.end().status == GoalStatus.STATUS_SUCCEEDED


def test_a_velocity_command_aborts_the_goal(
    sim: Program, probe: Any, turtle: str, rotate: Any
) -> None:
    mark = sim.mark()
    goal = Goal(probe, rotate, 2.5)
    goal.feedback(3)
    drive(probe, turtle, x=0.5)
    assert goal.end().status == GoalStatus.STATUS_ABORTED
    sim.wait_log("Velocity command received during rotation goal. Aborting goal", mark)
