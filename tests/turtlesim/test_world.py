"""turtlesim's world without ROS: Jazzy's numbers for the window, motion, the command timeout,
the walls, teleports, pens, names, rotation goals; the trails picture and its snapshots."""

from __future__ import annotations

import base64
import io
import json
import math
from dataclasses import dataclass, field

import pytest
from PIL import Image

from launchkit.stock.turtlesim.canvas import PathImage
from launchkit.stock.turtlesim.scene import SNAPSHOT_STROKES, SceneFeed, topics
from launchkit.stock.turtlesim.world import (
    HEIGHT_M,
    PI,
    UPDATE_PERIOD_S,
    WIDTH_M,
    Pen,
    Stroke,
    Teleport,
    Turtle,
    World,
    f32,
    normalize_angle,
)

MS = 1_000_000


def centre_turtle(image: int = 0) -> Turtle:
    world = World(lambda: image)
    turtle = world.spawn("", WIDTH_M / 2, HEIGHT_M / 2, 0.0, 0)
    assert turtle is not None
    return turtle


class Recorder:
    """Collects what an update draws and logs."""

    def __init__(self) -> None:
        self.strokes: list[Stroke] = []
        self.logs: list[tuple[str, str]] = []

    def draw(self, stroke: Stroke) -> None:
        self.strokes.append(stroke)

    def log(self, level: str, text: str) -> None:
        self.logs.append((level, text))


def run(turtle: Turtle, ticks: int, start_ns: int = 0, rec: Recorder | None = None) -> Recorder:
    """``ticks`` updates, 16 ms apart after ``start_ns``; the motion strokes go to ``rec`` too."""
    rec = rec or Recorder()
    for k in range(1, ticks + 1):
        step = turtle.update(UPDATE_PERIOD_S, start_ns + k * 16 * MS, rec.draw, rec.log)
        if step.stroke is not None:
            rec.draw(step.stroke)
    return rec


def test_the_window_and_turtle1_are_jazzys() -> None:
    assert (f"{WIDTH_M:f}", f"{HEIGHT_M:f}") == ("11.088889", "11.088889")
    turtle = centre_turtle()
    # the pose turtlesim publishes, and ros2 topic echo shows: 5.544444561004639
    assert (f32(turtle.x), f32(turtle.y), turtle.orient) == (5.544444561004639,) * 2 + (0.0,)
    assert turtle.pixel() == (250, 249)  # 249.500005 and 249.499995 rounded
    assert turtle.pen == Pen(179, 184, 255, 3) and turtle.pen_on


def test_angles_normalise_as_jazzys() -> None:
    assert normalize_angle(0.5) == 0.5
    assert normalize_angle(PI) == pytest.approx(-PI)
    assert normalize_angle(3.2) == pytest.approx(3.2 - 2 * PI)
    assert normalize_angle(-4.0) == pytest.approx(-4.0 + 2 * PI)


def test_a_command_moves_by_speed_times_16_ms_a_step_and_stops_after_one_second() -> None:
    turtle = centre_turtle()
    x0 = turtle.x
    turtle.command(2.0, 0.0, 0)
    rec = run(turtle, 80)
    # steps at 16, 32, ... 992 ms move; the one at 1008 ms sees the command older than 1 s
    assert turtle.x - x0 == pytest.approx(62 * 2.0 * 0.016)
    assert (turtle.lin_vel_x, turtle.ang_vel) == (0.0, 0.0)
    assert len(rec.strokes) == 62 and all(s.pen == Pen() for s in rec.strokes)
    assert rec.logs == []


def test_an_arc_turns_while_it_moves() -> None:
    turtle = centre_turtle()
    turtle.command(2.0, 1.8, 0)
    run(turtle, 62)
    assert turtle.orient == pytest.approx(normalize_angle(62 * 1.8 * 0.016))
    radius = 2.0 / 1.8
    # the centre of the circle is left of the start heading (east): (x0, y0 + r)
    assert math.hypot(turtle.x - WIDTH_M / 2, turtle.y - (HEIGHT_M / 2 + radius)) == pytest.approx(
        radius, abs=0.02
    )


def test_the_wall_clamps_and_says_where_from_in_jazzys_words() -> None:
    turtle = centre_turtle()
    turtle.x = 11.0
    turtle.command(2.0, 0.0, 0)
    rec = run(turtle, 3)
    assert turtle.x == WIDTH_M
    # the third step reaches 11.096; y is printed as Jazzy keeps it, down from the top edge
    assert rec.logs == [
        ("warn", "Oh no! I hit the wall! (Clamping from [x=11.096000, y=5.544444])")
    ]


def test_holonomic_turtles_move_sideways() -> None:
    turtle = centre_turtle()
    turtle.command(0.0, 0.0, 0, linear_y=1.0)
    run(turtle, 10)
    assert turtle.y - HEIGHT_M / 2 == pytest.approx(10 * 0.016, abs=1e-6)
    turtle.command(0.0, 0.0, 200 * MS)  # not holonomic: y speed stays as it was (as in Jazzy)
    assert turtle.lin_vel_y == 1.0


def test_teleports_apply_at_the_next_update_and_draw_with_the_pen() -> None:
    turtle = centre_turtle()
    turtle.teleport(Teleport(theta=PI / 2, linear=1.0, relative=True))
    assert turtle.y == pytest.approx(HEIGHT_M / 2)
    rec = run(turtle, 1)
    assert (turtle.x, turtle.y, turtle.orient) == pytest.approx(
        (WIDTH_M / 2, HEIGHT_M / 2 + 1, PI / 2)
    )
    assert len(rec.strokes) == 1
    assert rec.strokes[0].start == pytest.approx((249.5, 249.5 - 45.0), abs=1e-4)
    turtle.set_pen(0, 0, 0, 0, off=True)
    turtle.teleport(Teleport(x=1.0, y=20.0, theta=0.5))
    rec = run(turtle, 1, 16 * MS)
    assert (turtle.x, turtle.y, turtle.orient) == pytest.approx((1.0, HEIGHT_M, 0.5))
    assert rec.strokes == [] and rec.logs == []  # the pen is up; y above the top is put on it


def test_set_pen_width_zero_draws_one_pixel_wide_and_off_keeps_the_colour() -> None:
    turtle = centre_turtle()
    turtle.set_pen(255, 0, 0, 0, off=False)
    assert turtle.pen == Pen(255, 0, 0, 1)
    turtle.set_pen(1, 2, 3, 9, off=True)
    assert (turtle.pen, turtle.pen_on) == (Pen(255, 0, 0, 1), False)


def test_spawn_names_turtles_in_order_and_reset_starts_again() -> None:
    world = World(lambda: 4)
    first = world.spawn("", 1, 1, 0, 0)
    assert first is not None and first.name == "turtle1" and first.image == 4
    assert world.spawn("turtle2", 2, 2, 0, 0) is not None
    third = world.spawn("", 3, 3, 0, 0)
    assert third is not None and third.name == "turtle3"  # turtle2 is taken
    assert world.spawn("turtle3", 0, 0, 0, 0) is None
    assert world.kill("turtle1") is first and world.kill("turtle1") is None
    fourth = world.spawn("", 1, 1, 0, 0)
    assert fourth is not None and fourth.name == "turtle4"  # the counter goes on
    assert {t.name for t in world.reset()} == {"turtle2", "turtle3", "turtle4"}
    again = world.spawn("", 1, 1, 0, 0)
    assert again is not None and again.name == "turtle1" and list(world.turtles) == ["turtle1"]


@dataclass
class Goal:
    """A rotate_absolute goal as the action server would hand it over."""

    theta: float
    cancel: bool = False
    feedbacks: list[float] = field(default_factory=list)
    ended: list[tuple[str, float]] = field(default_factory=list)

    def cancel_requested(self) -> bool:
        return self.cancel

    def feedback(self, remaining: float) -> None:
        self.feedbacks.append(remaining)

    def succeed(self, delta: float) -> None:
        self.ended.append(("succeeded", delta))

    def canceled(self, delta: float) -> None:
        self.ended.append(("canceled", delta))

    def abort(self, delta: float) -> None:
        self.ended.append(("aborted", delta))


def test_a_rotation_goal_turns_at_one_radian_a_second_until_within_002() -> None:
    turtle = centre_turtle()
    goal = Goal(theta=1.5708)
    assert turtle.accept_goal(goal) is False
    rec = run(turtle, 200)
    assert [e[0] for e in goal.ended] == ["succeeded"]
    assert abs(turtle.orient - 1.5708) < 0.02 + 0.016
    assert goal.feedbacks[0] == pytest.approx(1.5708, abs=1e-6)
    assert goal.feedbacks == sorted(goal.feedbacks, reverse=True)
    assert goal.ended[0][1] == pytest.approx(-turtle.orient, abs=0.02)  # start minus now
    assert rec.logs == [("info", "Rotation goal completed successfully")]
    assert (turtle.ang_vel, turtle.goal) == (0.0, None)


def test_a_rotation_goal_is_canceled_aborted_by_a_command_or_by_a_newer_goal() -> None:
    turtle = centre_turtle()
    first = Goal(theta=-1.0)
    turtle.accept_goal(first)
    run(turtle, 5)
    assert turtle.ang_vel == -1.0
    second = Goal(theta=2.0)
    assert turtle.accept_goal(second) is True
    # the result is the turn as of the last step's start (Jazzy updates it before moving)
    assert first.ended == [("aborted", pytest.approx(4 * 0.016, abs=1e-6))]
    second.cancel = True
    rec = run(turtle, 1, 5 * 16 * MS)
    assert second.ended[0][0] == "canceled" and rec.logs == [("info", "Rotation goal canceled")]
    third = Goal(theta=2.0)
    turtle.accept_goal(third)
    run(turtle, 2, 6 * 16 * MS)
    assert turtle.command(0.0, 0.0, 9 * 16 * MS) is True
    assert [e[0] for e in third.ended] == ["aborted"] and turtle.goal is None


def test_the_trails_are_clear_white_under_a_new_turtle_and_the_pen_colour_on_a_trail() -> None:
    path = PathImage()
    assert path.color_at(250, 250) == (255, 255, 255)
    turtle = centre_turtle()
    turtle.command(2.0, 0.0, 0)
    rec = run(turtle, 10)
    for stroke in rec.strokes:
        path.stroke(stroke)
    assert path.color_at(*turtle.pixel()) == (179, 184, 255)
    assert path.color_at(250, 254) == (255, 255, 255)  # beside a 3-pixel line
    path.clear()
    assert path.color_at(*turtle.pixel()) == (255, 255, 255)


def test_snapshots_hold_the_trails_and_scenes_the_strokes_since() -> None:
    feed = SceneFeed(PathImage())
    first = json.loads(feed.snapshot(0.0) or "null")
    assert (first["serial"], first["upto"], first["png"]) == (1, 0, None)
    assert feed.snapshot(0.1) is None  # nothing new
    pen = Pen(255, 0, 0, 5)
    feed.stroke(Stroke(pen, (10.0, 10.0), (40.0, 10.0)))
    scene = json.loads(feed.scene((1, 2, 3), []) or "null")
    assert (scene["base"], scene["upto"], scene["background"]) == (0, 1, [1, 2, 3])
    assert scene["strokes"] == [[10.0, 10.0, 40.0, 10.0, 255, 0, 0, 5]]
    assert feed.scene((1, 2, 3), []) is None  # unchanged
    snapshot = json.loads(feed.snapshot(10.0) or "null")
    assert (snapshot["serial"], snapshot["upto"]) == (2, 1)
    picture = Image.open(io.BytesIO(base64.b64decode(snapshot["png"])))
    assert picture.size == (500, 500) and picture.getpixel((25, 10)) == (255, 0, 0, 255)
    assert json.loads(feed.scene((1, 2, 3), []) or "null")["strokes"] == []
    for k in range(SNAPSHOT_STROKES):
        feed.stroke(Stroke(pen, (k, 0.0), (k, 1.0)))
    assert json.loads(feed.snapshot(10.1) or "null")["upto"] == 1 + SNAPSHOT_STROKES
    feed.clear()
    assert json.loads(feed.snapshot(10.2) or "null")["png"] is None


def test_the_pictures_topics_are_hidden_under_the_node() -> None:
    assert topics("/turtlesim") == ("/_turtlesim/turtlesim/scene", "/_turtlesim/turtlesim/trails")
    assert topics("/turtlesim1/sim")[0] == "/_turtlesim/turtlesim1/sim/scene"
