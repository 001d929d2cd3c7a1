"""turtlesim_node as a process on the real transport, against Jazzy's numbers and log lines:
poses at the update rate, a command's 1 s timeout, the walls, spawn/kill/teleport/set_pen/clear/
reset, the colour sensor, the parameters and what they change in the picture."""

from __future__ import annotations

import itertools
import json
import math
import re
import subprocess
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.rcl_interfaces.msg import Parameter, ParameterValue
from launchkit.ros.msgs.rcl_interfaces.srv import SetParameters
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.std_srvs.srv import Empty
from launchkit.ros.msgs.turtlesim.msg import Color, Pose
from launchkit.ros.msgs.turtlesim.srv import (
    Kill,
    SetPen,
    Spawn,
    TeleportAbsolute,
    TeleportRelative,
)

import launchkit.ros as ros
from launchkit.stock.turtlesim.qos import TOPIC_QOS
from tests.turtlesim.conftest import NODE, Program, call, python, spin_until

CENTRE = 5.544444561004639  # turtle1's x and y, as ros2 topic echo prints them
STEP = 2.0 * 0.016  # a step at 2 m/s
LOG = re.compile(r"^\[(INFO|WARN|ERROR)\] \[\d+\.\d+\] \[turtlesim\]: (.*)$")


def messages(sim: Program, after: int = 0) -> list[tuple[str, str]]:
    """The node's log lines from ``after`` on, as (level, message)."""
    found = []
    for line in sim.err[after:]:
        match = LOG.match(line)
        if match:
            found.append((match[1], match[2]))
    return found


@pytest.fixture(scope="module")
def sim(programs: Callable[..., Program]) -> Program:
    """One turtlesim_node for the module (no viewer: the panel has tests of its own)."""
    program = programs(*python(NODE, "--no-viewer"))
    program.wait_log("Spawning turtle [turtle1]")
    return program


#: The probe's side of turtlesim's topics: reliable as the node's, but deep enough that a test
#: process the machine leaves waiting loses none of them (the node's depth 7 is its own choice).
PROBE_QOS = ros.QoSProfile(depth=10_000, reliability=ros.ReliabilityPolicy.RELIABLE)


class Watch:
    """What the probe hears of a topic: (the time the node published it, message)."""

    def __init__(self, probe: Any, msg_type: Any, topic: str, qos: Any = PROBE_QOS) -> None:
        self.probe = probe
        self.got: list[tuple[float, Any]] = []
        self.sub = probe.create_subscription(msg_type, topic, self._heard, qos)

    def _heard(self, msg: Any, info: Any) -> None:
        # the publisher's stamp, not the arrival: a busy machine delivers late and in bursts
        self.got.append((info["source_timestamp"] / 1e9, msg))

    def last(self) -> Any:
        return self.got[-1][1]

    def wait(self, predicate: Callable[[Any], bool], what: str) -> Any:
        """Spin until the latest message satisfies ``predicate``; that message."""
        spin_until(self.probe, lambda: bool(self.got) and predicate(self.last()), what)
        return self.last()

    def settle(self, what: str) -> Any:
        """The pose once the turtle stands still (two poses in a row at rest, equal)."""

        def still() -> bool:
            if len(self.got) < 2:
                return False
            (_, a), (_, b) = self.got[-2:]
            return a.linear_velocity == 0.0 and a.angular_velocity == 0.0 and a == b

        spin_until(self.probe, still, what)
        return self.last()


@pytest.fixture
def fresh(sim: Program, probe: Any) -> Iterator[Program]:
    """The module's turtlesim, reset (turtle1 alone at the centre, no trails)."""
    mark = sim.mark()
    call(probe, Empty, "/reset")
    sim.wait_log("Spawning turtle [turtle1]", mark)
    yield sim


@pytest.fixture
def watch(probe: Any) -> Iterator[Callable[..., Watch]]:
    """Subscribe the probe to topics for one test."""
    made: list[Watch] = []

    def make(msg_type: Any, topic: str, qos: Any = PROBE_QOS) -> Watch:
        made.append(Watch(probe, msg_type, topic, qos))
        return made[-1]

    yield make
    for w in made:
        probe.destroy_subscription(w.sub)


def drive(probe: Any, turtle: str, x: float = 0.0, z: float = 0.0, y: float = 0.0) -> None:
    """Publish one velocity command to ``turtle`` (once its subscription is matched)."""
    topic = f"/{turtle}/cmd_vel"
    publisher = probe.create_publisher(Twist, topic, TOPIC_QOS)
    try:
        spin_until(probe, lambda: probe.count_subscribers(topic) > 0, f"a subscriber of {topic}")
        spin_until(probe, lambda: publisher.get_subscription_count() > 0, f"{topic} matched")
        publisher.publish(Twist(linear=Vector3(x=x, y=y), angular=Vector3(z=z)))
    finally:
        probe.destroy_publisher(publisher)


def test_it_starts_as_jazzys_turtlesim(sim: Program, probe: Any, watch: Any) -> None:
    def topics() -> set[str]:
        return {name for name, _ in probe.get_topic_names_and_types()}

    assert messages(sim)[:2] == [
        ("INFO", "Starting turtlesim with node name /turtlesim"),
        ("INFO", "Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]"),
    ]
    poses = watch(Pose, "/turtle1/pose")
    pose = poses.wait(lambda p: True, "a pose of turtle1")
    assert (pose.x, pose.y, pose.theta) == (CENTRE, CENTRE, 0.0)
    spin_until(
        probe,
        lambda: len({"/turtle1/pose", "/turtle1/color_sensor", "/turtle1/cmd_vel"} & topics()) == 3,
        "turtle1's topics in the graph",
    )
    names = dict(probe.get_topic_names_and_types())
    assert names["/turtle1/pose"] == ["turtlesim/msg/Pose"]
    assert names["/turtle1/color_sensor"] == ["turtlesim/msg/Color"]
    assert names["/turtle1/cmd_vel"] == ["geometry_msgs/msg/Twist"]
    for srv_type, name in [
        (Spawn, "/spawn"),
        (Kill, "/kill"),
        (Empty, "/clear"),
        (Empty, "/reset"),
        (SetPen, "/turtle1/set_pen"),
        (TeleportAbsolute, "/turtle1/teleport_absolute"),
        (TeleportRelative, "/turtle1/teleport_relative"),
    ]:
        client = probe.create_client(srv_type, name)  # matches a server of this type only
        try:
            assert client.wait_for_service(timeout_sec=20), name
        finally:
            probe.destroy_client(client)


def test_poses_come_at_the_update_rate(fresh: Program, watch: Any, probe: Any) -> None:
    poses = watch(Pose, "/turtle1/pose")
    spin_until(probe, lambda: len(poses.got) >= 120, "120 poses")
    span = poses.got[-1][0] - poses.got[0][0]
    rate = (len(poses.got) - 1) / span
    # 16 ms a step: 62.5 a second; fewer only when a busy machine delays the timer
    assert 25 < rate < 66, rate


def test_a_command_moves_2_m_in_its_second_then_the_turtle_stops(
    fresh: Program, probe: Any, watch: Any
) -> None:
    poses = watch(Pose, "/turtle1/pose")
    poses.wait(lambda p: True, "a pose")
    drive(probe, "turtle1", x=2.0)
    poses.wait(lambda p: p.linear_velocity == 2.0, "turtle1 moving")
    end = poses.wait(lambda p: p.linear_velocity == 0.0, "turtle1 stopping by itself")
    moving = [(t, p) for t, p in poses.got if p.linear_velocity == 2.0]
    steps = [b.x - a.x for (_, a), (_, b) in itertools.pairwise(moving)]
    assert all(s == pytest.approx(STEP, abs=1e-5) for s in steps), steps
    # one step per 16 ms update for as long as the command is younger than 1 s: 62 or 63
    assert len(moving) <= 63
    assert end.x - CENTRE == pytest.approx(len(moving) * STEP, abs=1e-4)
    # ~2 m (62 or 63 steps: test_world checks Jazzy's arithmetic); fewer steps only when a
    # busy machine delays the timer, as it would Jazzy's
    assert 10 * STEP <= end.x - CENTRE <= 63 * STEP + 1e-4
    # by the node's own clock: the command came after the last pose at rest and is more than
    # 1 s old at the first pose stopped; it was younger than 1 s at the last pose moving (the
    # slack is the time between reading the clock and publishing, within one update)
    rest_before = max(t for t, p in poses.got if p.linear_velocity == 0.0 and t < moving[0][0])
    stopped_at = next(t for t, p in poses.got if p.linear_velocity == 0.0 and t > moving[0][0])
    assert stopped_at - rest_before > 1.0
    assert moving[-1][0] - moving[0][0] < 1.0 + 0.25
    assert (end.y, end.theta, end.angular_velocity) == (CENTRE, 0.0, 0.0)


def test_the_wall_clamps_and_says_so(fresh: Program, probe: Any, watch: Any) -> None:
    poses = watch(Pose, "/turtle1/pose")
    call(probe, TeleportAbsolute, "/turtle1/teleport_absolute", x=10.9, y=CENTRE, theta=0.0)
    poses.wait(lambda p: p.x == pytest.approx(10.9), "turtle1 teleported near the east wall")
    mark = fresh.mark()
    drive(probe, "turtle1", x=2.0)
    line = fresh.wait_log("Oh no! I hit the wall!", mark)
    assert line.startswith("[WARN] ")
    # 10.9 (as a float) + 6 steps of 0.032 passes 11.088889; y as Jazzy keeps it (from the top)
    assert line.endswith("Oh no! I hit the wall! (Clamping from [x=11.092000, y=5.544444])")
    pose = poses.wait(lambda p: p.x > 11.0 and p.linear_velocity == 0.0, "turtle1 stopping")
    assert pose.x == pytest.approx(499 / 45, abs=1e-5)


def test_spawn_and_kill(fresh: Program, probe: Any, watch: Any) -> None:
    mark = fresh.mark()
    assert call(probe, Spawn, "/spawn", x=2.0, y=2.0, theta=0.2, name="").name == "turtle2"
    # the answer may arrive before the test has read the node's log line: wait for the line
    line = fresh.wait_log("Spawning turtle [turtle2]", mark)
    assert line.startswith("[INFO] ")
    assert line.endswith("at x=[2.000000], y=[2.000000], theta=[0.200000]")
    pose = watch(Pose, "/turtle2/pose").wait(lambda p: True, "a pose of turtle2")
    assert (pose.x, pose.y, pose.theta) == pytest.approx((2.0, 2.0, 0.2))
    assert call(probe, Spawn, "/spawn", x=1.0, y=1.0, theta=0.0, name="leo").name == "leo"
    assert call(probe, Spawn, "/spawn", x=1.0, y=1.0, theta=0.0, name="leo").name == ""
    line = fresh.wait_log("A turtle named [leo] already exists", mark)
    assert line.startswith("[ERROR] ") and line.endswith("]: A turtle named [leo] already exists")
    call(probe, Kill, "/kill", name="turtle2")
    spin_until(probe, lambda: probe.count_publishers("/turtle2/pose") == 0, "turtle2 gone")
    call(probe, Kill, "/kill", name="nobody")
    line = fresh.wait_log("Tried to kill turtle [nobody], which does not exist", mark)
    assert line.startswith("[ERROR] ")
    assert call(probe, Spawn, "/spawn", x=3.0, y=3.0, theta=0.0, name="").name == "turtle3"


def test_teleport_relative(fresh: Program, probe: Any, watch: Any) -> None:
    poses = watch(Pose, "/turtle1/pose")
    call(probe, TeleportRelative, "/turtle1/teleport_relative", linear=1.0, angular=math.pi / 2)
    pose = poses.wait(lambda p: p.theta != 0.0, "turtle1 turned")
    assert (pose.x, pose.y, pose.theta) == pytest.approx(
        (CENTRE, CENTRE + 1, math.pi / 2), abs=1e-5
    )


def test_the_colour_sensor_reads_the_trails_under_the_turtle(
    fresh: Program, probe: Any, watch: Any
) -> None:
    colors = watch(Color, "/turtle1/color_sensor")
    poses = watch(Pose, "/turtle1/pose")
    rgb: Callable[[Any], tuple[int, int, int]] = lambda c: (c.r, c.g, c.b)  # noqa: E731
    # nothing drawn: the trails picture is transparent white (the background is not in it)
    assert rgb(colors.wait(lambda c: True, "a colour")) == (255, 255, 255)
    drive(probe, "turtle1", x=2.0)
    poses.wait(lambda p: p.linear_velocity == 2.0, "turtle1 moving")
    poses.settle("turtle1 at rest")
    colors.wait(lambda c: rgb(c) == (179, 184, 255), "the default pen's colour under turtle1")
    call(probe, SetPen, "/turtle1/set_pen", r=255, g=0, b=0, width=5, off=0)
    drive(probe, "turtle1", z=2.0)  # turning on the spot draws nothing: the turtle stays put
    poses.wait(lambda p: p.angular_velocity == 2.0, "turtle1 turning")
    drive(probe, "turtle1", x=1.0)
    poses.wait(lambda p: p.linear_velocity == 1.0, "turtle1 moving")
    # at rest before the pen goes up: a turtle still moving would carry on past the red trail
    # (pen up) while the services below are called, the longer the busier the machine
    poses.settle("turtle1 at rest at the end of the red trail")
    colors.wait(lambda c: rgb(c) == (255, 0, 0), "the red pen under turtle1")
    call(probe, SetPen, "/turtle1/set_pen", r=0, g=0, b=0, width=0, off=1)
    call(probe, TeleportRelative, "/turtle1/teleport_relative", linear=2.0, angular=0.0)
    colors.wait(lambda c: rgb(c) == (255, 255, 255), "no trail under turtle1 after a pen-up jump")
    call(probe, TeleportRelative, "/turtle1/teleport_relative", linear=-2.0, angular=0.0)
    colors.wait(lambda c: rgb(c) == (255, 0, 0), "the red trail again, back where it was drawn")
    mark = fresh.mark()
    call(probe, Empty, "/clear")
    fresh.wait_log("Clearing turtlesim.", mark)
    colors.wait(lambda c: rgb(c) == (255, 255, 255), "the trails cleared")


def test_reset_leaves_turtle1_alone_at_the_centre(fresh: Program, probe: Any, watch: Any) -> None:
    call(probe, Spawn, "/spawn", x=1.0, y=1.0, theta=0.0, name="")
    call(probe, TeleportAbsolute, "/turtle1/teleport_absolute", x=1.0, y=9.0, theta=1.0)
    poses = watch(Pose, "/turtle1/pose")
    poses.wait(lambda p: p.x == pytest.approx(1.0), "turtle1 teleported")
    mark = fresh.mark()
    call(probe, Empty, "/reset")
    fresh.wait_log("Spawning turtle [turtle1]", mark)
    assert messages(fresh, mark)[:2] == [
        ("INFO", "Resetting turtlesim."),
        ("INFO", "Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]"),
    ]
    pose = poses.wait(lambda p: p.x == CENTRE, "turtle1 back at the centre")
    assert (pose.y, pose.theta) == (CENTRE, 0.0)
    spin_until(probe, lambda: probe.count_publishers("/turtle2/pose") == 0, "turtle2 removed")


def set_parameter(probe: Any, name: str, value: ParameterValue) -> Any:
    response = call(
        probe,
        SetParameters,
        "/turtlesim/set_parameters",
        parameters=[Parameter(name=name, value=value)],
    )
    return response.results[0]


def test_the_background_parameters_change_the_picture(
    fresh: Program, probe: Any, watch: Any
) -> None:
    latched = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
    scene = watch(String, "/_turtlesim/turtlesim/scene", latched)
    background: Callable[[Any], list[int]] = lambda m: json.loads(m.data)["background"]  # noqa: E731
    assert background(scene.wait(lambda m: True, "the scene")) == [69, 86, 255]
    assert set_parameter(
        probe, "background_r", ParameterValue(type=2, integer_value=150)
    ).successful
    scene.wait(lambda m: background(m) == [150, 86, 255], "the red background parameter drawn")
    assert set_parameter(probe, "background_b", ParameterValue(type=2, integer_value=0)).successful
    scene.wait(lambda m: background(m) == [150, 86, 0], "the blue one too")
    for name, value in (("background_r", 69), ("background_b", 255)):
        set_parameter(probe, name, ParameterValue(type=2, integer_value=value))
    scene.wait(lambda m: background(m) == [69, 86, 255], "the default background again")


def test_holonomic_turtles_move_sideways(fresh: Program, probe: Any, watch: Any) -> None:
    poses = watch(Pose, "/turtle1/pose")
    drive(probe, "turtle1", y=1.0, z=0.5)  # not holonomic: sideways speed is ignored
    poses.wait(lambda p: p.angular_velocity == 0.5, "turtle1 turning (the command arrived)")
    pose = poses.settle("turtle1 at rest")
    assert (pose.x, pose.y) == (CENTRE, CENTRE) and pose.theta > 0.0
    call(probe, TeleportAbsolute, "/turtle1/teleport_absolute", x=CENTRE, y=CENTRE, theta=0.0)
    poses.wait(lambda p: p.theta == 0.0, "turtle1 facing east again")
    set_parameter(probe, "holonomic", ParameterValue(type=1, bool_value=True))
    try:
        drive(probe, "turtle1", y=1.0)
        pose = poses.wait(lambda p: p.y > CENTRE + 0.1, "turtle1 moving sideways (+y)")
        assert (pose.x, pose.theta, pose.linear_velocity) == (CENTRE, 0.0, 1.0)
    finally:
        set_parameter(probe, "holonomic", ParameterValue(type=1, bool_value=False))


@pytest.mark.parametrize(
    ("argument", "words"),
    [("--bogus", "unrecognized arguments: --bogus"), ("--viewer-port=70000", "70000")],
)
def test_a_wrong_argument_is_one_line_and_status_2(argument: str, words: str) -> None:
    done = subprocess.run(
        python(NODE, argument), capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL
    )
    assert done.returncode == 2
    assert done.stderr.startswith("turtlesim_node: error: ") and words in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and "Traceback" not in done.stderr
