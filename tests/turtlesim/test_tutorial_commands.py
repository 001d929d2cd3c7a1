"""The beginner tutorials' turtlesim commands, typed as a learner types them (``launchkit`` for
``ros2``): turtlesim_node with its viewer address, topic pub, service call, param set, the
teleop in a terminal, draw_square, mimic, and multisim.launch.py."""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
from collections.abc import Callable, Iterator
from typing import Any

import pexpect
import pytest
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.turtlesim.msg import Pose

import launchkit.ros as ros
from launchkit.stock.turtlesim.qos import TOPIC_QOS
from launchkit.testing._isolation import free_loopback_port
from tests.turtlesim.conftest import DEADLINE, Program, spin_until

LAUNCHKIT = [sys.executable, "-m", "launchkit"]
CENTRE = 5.544444561004639


def launchkit(command: str) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit COMMAND`` (written as a shell line) to its end."""
    return subprocess.run(
        [*LAUNCHKIT, *shlex.split(command)],
        capture_output=True,
        text=True,
        timeout=120,
        stdin=subprocess.DEVNULL,
    )


@pytest.fixture(scope="module")
def sim(programs: Callable[..., Program]) -> Program:
    """``launchkit exec turtlesim turtlesim_node``, its viewer on a free port."""
    program = programs(*LAUNCHKIT, "exec", "turtlesim", "turtlesim_node", env=VIEWER_ANY_PORT)
    program.wait_log("Spawning turtle [turtle1]")
    return program


VIEWER_ANY_PORT = {"LAUNCHKIT_VIEWER_PORT": "0"}


@pytest.fixture
def poses(probe: Any) -> Iterator[Callable[[str], list[Pose]]]:
    """Collect a turtle's poses: ``poses("turtle1")`` is the list they arrive in."""
    made: list[Any] = []

    def collect(turtle: str) -> list[Pose]:
        got: list[Pose] = []
        made.append(probe.create_subscription(Pose, f"/{turtle}/pose", got.append, TOPIC_QOS))
        return got

    yield collect
    for subscription in made:
        probe.destroy_subscription(subscription)


def test_turtlesim_node_prints_where_to_see_it_and_appears_as_turtlesim(sim: Program) -> None:
    line = sim.wait_out("viewer: ")
    assert line.startswith("viewer: http://127.0.0.1:") and line.endswith(" (open it in a browser)")
    assert "Starting turtlesim with node name /turtlesim" in sim.err[0]
    listed = launchkit("node list")
    assert listed.returncode == 0 and listed.stdout.split() == ["/turtlesim"]  # viewer hidden
    topics = launchkit("topic list").stdout.split()
    assert {"/turtle1/cmd_vel", "/turtle1/color_sensor", "/turtle1/pose"} <= set(topics)
    assert not [t for t in topics if t.startswith("/_")]


def test_topic_pub_drives_the_turtle_along_an_arc(sim: Program, probe: Any, poses: Any) -> None:
    got = poses("turtle1")
    done = launchkit(
        'topic pub --once /turtle1/cmd_vel geometry_msgs/msg/Twist "{linear: {x: 2.0}, '
        'angular: {z: 1.8}}"'
    )
    assert done.returncode == 0, done.stderr
    spin_until(probe, lambda: any(p.angular_velocity == pytest.approx(1.8) for p in got), "arc")
    spin_until(
        probe,
        lambda: got[-1].angular_velocity == 0.0 and got[-1].theta != 0.0,
        "the turtle stopping after its second",
    )
    end = got[-1]
    # on the circle of radius 2/1.8 about (x0, y0 + r), turned by as much as it went round
    radius = 2.0 / 1.8
    assert (end.x - CENTRE) ** 2 + (end.y - CENTRE - radius) ** 2 == pytest.approx(
        radius**2, abs=0.05
    )
    assert 0.3 < end.theta <= 1.8 + 0.03  # 1.8 rad in its second, less on a delayed timer


def test_service_call_spawns_a_second_turtle(sim: Program, probe: Any, poses: Any) -> None:
    done = launchkit(
        "service call /spawn turtlesim/srv/Spawn \"{x: 2, y: 2, theta: 0.2, name: ''}\""
    )
    assert done.returncode == 0, done.stderr
    assert "turtlesim.srv.Spawn_Response(name='turtle2')" in done.stdout
    sim.wait_log("Spawning turtle [turtle2] at x=[2.000000], y=[2.000000], theta=[0.200000]")
    got = poses("turtle2")
    spin_until(probe, lambda: bool(got), "a pose of turtle2")
    assert (got[-1].x, got[-1].y) == pytest.approx((2.0, 2.0))


def test_param_set_changes_the_background(sim: Program, probe: Any) -> None:
    latched = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
    scenes: list[Any] = []
    sub = probe.create_subscription(String, "/_turtlesim/turtlesim/scene", scenes.append, latched)
    try:
        done = launchkit("param set /turtlesim background_r 150")
        assert (done.returncode, done.stdout.strip()) == (0, "Set parameter successful")

        def red() -> int | None:
            return json.loads(scenes[-1].data)["background"][0] if scenes else None

        spin_until(probe, lambda: red() == 150, "the picture's background with red 150")
        assert launchkit("param get /turtlesim background_r").stdout.strip() == (
            "Integer value is: 150"
        )
    finally:
        probe.destroy_subscription(sub)
        launchkit("param set /turtlesim background_r 69")


def test_teleop_key_drives_turtle1_with_the_arrow_and_action_keys(
    sim: Program, probe: Any, poses: Any
) -> None:
    got = poses("turtle1")
    debug = ["--ros-args", "--log-level", "teleop_turtle:=debug"]  # its goal responses
    command = shlex.join([*LAUNCHKIT, "exec", "turtlesim", "turtle_teleop_key", *debug])
    child = pexpect.spawn("/bin/sh", ["-c", f"{command}; echo EXIT=$?"], encoding="utf-8")
    try:
        child.expect_exact("Reading from keyboard", timeout=DEADLINE)
        child.expect_exact(
            "Use G|B|V|C|D|E|R|T keys to rotate to absolute orientations. 'F' to cancel a rotation."
        )
        child.expect_exact("'Q' to quit.")
        spin_until(
            probe, lambda: probe.count_publishers("/turtle1/cmd_vel") > 0, "the teleop's publisher"
        )
        child.send("\x1b[A")  # the up arrow: forward at scale_linear (2.0)
        spin_until(probe, lambda: any(p.linear_velocity == 2.0 for p in got), "turtle1 forward")
        child.send("\x1b[D")  # the left arrow: turn left at scale_angular (2.0)
        spin_until(probe, lambda: any(p.angular_velocity == 2.0 for p in got), "turtle1 turning")
        child.send("r")  # rotate_absolute to 1.5708 (north)
        child.expect_exact("Goal response received", timeout=DEADLINE)
        spin_until(
            probe, lambda: any(abs(p.theta - 1.5708) < 0.02 for p in got), "turtle1 facing north"
        )
        mark = sim.mark()
        child.send("c")  # to -2.3562 (south-west), the long way round, canceled by F
        child.expect_exact("Goal response received", timeout=DEADLINE)  # F cancels this one
        child.send("f")
        sim.wait_log("Rotation goal canceled", mark)
        spin_until(probe, lambda: got[-1].angular_velocity == 0.0, "turtle1 stopped")
        assert abs(got[-1].theta + 2.3562) > 0.1  # short of south-west
        child.send("q")
        child.expect_exact("EXIT=0", timeout=DEADLINE)
    finally:
        if child.isalive():
            child.terminate(force=True)
        child.close()


def test_draw_square_resets_and_drives_the_first_side(
    sim: Program, programs: Callable[..., Program]
) -> None:
    mark = sim.mark()
    square = programs(*LAUNCHKIT, "exec", "turtlesim", "draw_square")
    sim.wait_log("Resetting turtlesim.", mark)
    square.wait_log("New goal [7.544445 5.544445, 0.000000]")
    first = square.wait_log("Reached goal")
    turn = square.wait_log("New goal", square.err.index(first))
    found = re.search(r"New goal \[(\S+) (\S+), 1\.570796\]$", turn)
    assert turn.startswith("[INFO] ") and found, turn
    # where the first side ended, a quarter turn on: straight east, stopped once within 0.1 m
    # of its goal (a busy machine's late stop command lets it run on a little, as in Jazzy)
    x, y = float(found[1]), float(found[2])
    assert y == pytest.approx(5.544445, abs=1e-3)
    assert 7.544445 - 0.1 < x < 7.544445 + 0.5
    square.stop()


def test_mimic_copies_one_turtle_to_another(sim: Program, probe: Any, poses: Any) -> None:
    assert (
        launchkit(
            "service call /spawn turtlesim/srv/Spawn \"{x: 2, y: 8, theta: 0.0, name: 'copy'}\""
        ).returncode
        == 0
    )
    got = poses("copy")
    mimic = Program(
        [
            *LAUNCHKIT,
            "exec",
            "turtlesim",
            "mimic",
            "--ros-args",
            "-r",
            "input/pose:=/turtle1/pose",
            "-r",
            "output/cmd_vel:=/copy/cmd_vel",
        ]
    )
    try:
        spin_until(probe, lambda: probe.count_publishers("/copy/cmd_vel") > 0, "mimic's publisher")
        done = launchkit(
            'topic pub --once /turtle1/cmd_vel geometry_msgs/msg/Twist "{linear: {x: 1.0}, '
            'angular: {z: -0.5}}"'
        )
        assert done.returncode == 0, done.stderr
        spin_until(
            probe,
            lambda: any(p.linear_velocity == 1.0 and p.angular_velocity == -0.5 for p in got),
            "the copy moving as turtle1 does",
        )
    finally:
        mimic.stop()


def test_multisim_launch_runs_two_turtlesims_and_one_viewer(tmp_path: Any, router: str) -> None:
    port = free_loopback_port()
    launch = Program(
        [*LAUNCHKIT, "run", "turtlesim", "multisim.launch.py"],
        env={"LAUNCHKIT_VIEWER_PORT": str(port)},
    )
    try:
        for ns in ("turtlesim1", "turtlesim2"):
            launch.wait_out(f"Starting turtlesim with node name /{ns}/turtlesim")
        served = launch.wait_out(f"viewer: http://127.0.0.1:{port}/ (open it in a browser)")
        shared = launch.wait_out(f"viewer: http://127.0.0.1:{port}/ (the viewer already running")
        assert served != shared
        topics = launchkit("topic list").stdout.split()
        assert {"/turtlesim1/turtle1/pose", "/turtlesim2/turtle1/pose"} <= set(topics)
    finally:
        assert launch.stop() == 0
