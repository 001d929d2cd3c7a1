"""The turtles' world as ROS 2 Jazzy's turtlesim computes it: pure state and arithmetic, no ROS.

Jazzy's window is 500 x 500 pixels and a metre is the height of a turtle image (45 pixels), so
the world is ``(500 - 1) / 45 = 11.088889`` metres square with ``turtle1`` spawned at its
centre. Positions are kept as Jazzy keeps them, in metres with ``y`` growing *down* from the top
edge (the drawing's orientation); poses report ``y`` growing up. The wall message prints the
kept (downward) coordinates, as Jazzy's does.

Every update moves a turtle by its velocity times a fixed ``dt`` (the 16 ms of the update
timer, whatever time really passed, as Jazzy does), after applying the teleports asked for since
the last update and driving an active ``rotate_absolute`` goal. A turtle whose last velocity
command is older than one second stops.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

#: The window's size in pixels.
WIDTH_PX = 500
HEIGHT_PX = 500
#: Pixels a metre: the height of the turtle images.
METER_PX = 45.0
WIDTH_M = (WIDTH_PX - 1) / METER_PX
HEIGHT_M = (HEIGHT_PX - 1) / METER_PX
#: How many turtle images Jazzy has to choose from (ardent ... jazzy, rolling).
TURTLE_IMAGES = 11
#: The update timer's period, which is also each step's ``dt``.
UPDATE_PERIOD_S = 0.016
#: A turtle stops when its last velocity command is older than this.
COMMAND_TIMEOUT_NS = 1_000_000_000
#: Jazzy's value of pi (a macro with eight decimals), used by its angle normalisation.
PI = 3.14159265
#: A rotate_absolute goal is reached within this many radians.
ROTATION_TOLERANCE = 0.02

DEFAULT_PEN = (0xB3, 0xB8, 0xFF)
DEFAULT_PEN_WIDTH = 3
DEFAULT_BACKGROUND = (0x45, 0x56, 0xFF)


def normalize_angle(angle: float) -> float:
    """``angle`` brought into [-pi, pi), with Jazzy's arithmetic."""
    return angle - 2.0 * PI * math.floor((angle + PI) / (2.0 * PI))


def f32(value: float) -> float:
    """``value`` rounded to a 32-bit float, as C++ ``static_cast<float>`` rounds it."""
    result: float = struct.unpack("f", struct.pack("f", value))[0]
    return result


@dataclass(frozen=True)
class Pen:
    """A turtle's pen: colour and width in pixels."""

    r: int = DEFAULT_PEN[0]
    g: int = DEFAULT_PEN[1]
    b: int = DEFAULT_PEN[2]
    width: int = DEFAULT_PEN_WIDTH


@dataclass(frozen=True)
class Teleport:
    """A teleport asked for; applied at the turtle's next update."""

    x: float = 0.0
    y: float = 0.0
    theta: float = 0.0
    linear: float = 0.0
    relative: bool = False


@dataclass(frozen=True)
class PoseReport:
    """What a turtle's ``pose`` topic says after an update."""

    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float


@dataclass(frozen=True)
class Stroke:
    """A pen stroke between two points in pixels (y down)."""

    pen: Pen
    start: tuple[float, float]
    end: tuple[float, float]


@dataclass(frozen=True)
class Step:
    """What one update of a turtle gives: its pose, and the stroke it drew moving (if any)."""

    pose: PoseReport
    stroke: Stroke | None


class RotationGoal(Protocol):
    """An accepted ``rotate_absolute`` goal, as the turtle drives it (the action server's goal
    handle, seen through the calls the turtle makes)."""

    @property
    def theta(self) -> float:
        """The heading asked for, in radians."""

    def cancel_requested(self) -> bool:
        """Whether a client asked to cancel the goal."""

    def feedback(self, remaining: float) -> None:
        """Send the feedback: radians still to turn."""

    def succeed(self, delta: float) -> None:
        """End the goal as reached; ``delta`` is the result (radians turned)."""

    def canceled(self, delta: float) -> None:
        """End the goal as canceled."""

    def abort(self, delta: float) -> None:
        """End the goal as aborted (a velocity command or a newer goal came)."""


#: ``draw(stroke)``: draw a pen stroke.
Draw = Callable[[Stroke], None]
#: ``log(level, text)`` with level "info" or "warn".
Log = Callable[[str, str], None]


@dataclass
class Turtle:
    """One turtle's state and the update that moves it."""

    name: str
    x: float
    y_down: float
    orient: float
    image: int
    last_command_ns: int
    lin_vel_x: float = 0.0
    lin_vel_y: float = 0.0
    ang_vel: float = 0.0
    pen_on: bool = True
    pen: Pen = field(default_factory=Pen)
    teleports: list[Teleport] = field(default_factory=list)
    goal: RotationGoal | None = None
    goal_start_orient: float = 0.0
    goal_delta: float = 0.0

    @property
    def y(self) -> float:
        """``y`` in world coordinates (up from the bottom edge)."""
        return HEIGHT_M - self.y_down

    # -- what the turtle's services and topics ask -------------------------------------------

    def command(
        self, linear_x: float, angular_z: float, now_ns: int, linear_y: float | None = None
    ) -> bool:
        """A velocity command (``cmd_vel``); ``linear_y`` is given only for holonomic turtles
        (otherwise the sideways speed stays as it was, as in Jazzy). Returns whether an active
        rotation goal was aborted by it."""
        self.last_command_ns = now_ns
        self.lin_vel_x = linear_x
        if linear_y is not None:
            self.lin_vel_y = linear_y
        self.ang_vel = angular_z
        if self.goal is None:
            return False
        self.goal.abort(self.goal_delta)
        self.goal = None
        return True

    def set_pen(self, r: int, g: int, b: int, width: int, off: bool) -> None:
        """``set_pen``: lift the pen, or put it down with a colour and width (0: 1 pixel)."""
        self.pen_on = not off
        if not off:
            self.pen = Pen(r, g, b, width if width != 0 else 1)

    def teleport(self, request: Teleport) -> None:
        """``teleport_absolute`` / ``teleport_relative``: applied at the next update."""
        self.teleports.append(request)

    def accept_goal(self, goal: RotationGoal) -> bool:
        """A new ``rotate_absolute`` goal; returns whether an active one was aborted for it."""
        aborted = self.goal is not None
        if self.goal is not None:
            self.goal.abort(self.goal_delta)
        self.goal = goal
        self.goal_delta = 0.0
        self.goal_start_orient = self.orient
        return aborted

    # -- the update ---------------------------------------------------------------------------

    def update(self, dt: float, now_ns: int, draw: Draw, log: Log) -> Step:
        """One step: teleports, the rotation goal, the command timeout, motion, the walls.

        The strokes of teleports go to ``draw`` at once; the wall message to ``log``. The
        stroke of the motion itself is returned with the pose, for the caller to draw after
        reading the colour sensor (Jazzy reads the pixel under the turtle before drawing it).
        """
        for request in self.teleports:
            old = self._point()
            if request.relative:
                self.orient += request.theta
                self.x += math.cos(self.orient) * request.linear
                self.y_down += -math.sin(self.orient) * request.linear
            else:
                self.x = request.x
                self.y_down = max(0.0, HEIGHT_M - request.y)
                self.orient = request.theta
            if self.pen_on:
                draw(Stroke(self.pen, self._point(), old))
        self.teleports.clear()

        if self.goal is not None:
            self._drive_goal(now_ns, log)

        if now_ns - self.last_command_ns > COMMAND_TIMEOUT_NS:
            self.lin_vel_x = self.lin_vel_y = self.ang_vel = 0.0

        old = self._point()
        self.orient = normalize_angle(self.orient + self.ang_vel * dt)
        cos, sin = math.cos(self.orient), math.sin(self.orient)
        self.x += cos * self.lin_vel_x * dt - sin * self.lin_vel_y * dt
        self.y_down -= cos * self.lin_vel_y * dt + sin * self.lin_vel_x * dt

        if not (0.0 <= self.x <= WIDTH_M and 0.0 <= self.y_down <= HEIGHT_M):
            log(
                "warn",
                f"Oh no! I hit the wall! (Clamping from [x={self.x:f}, y={self.y_down:f}])",
            )
        self.x = min(max(self.x, 0.0), WIDTH_M)
        self.y_down = min(max(self.y_down, 0.0), HEIGHT_M)

        pose = PoseReport(
            self.x,
            self.y,
            self.orient,
            math.sqrt(self.lin_vel_x**2 + self.lin_vel_y**2),
            self.ang_vel,
        )
        moved = self._point() != old
        stroke = Stroke(self.pen, self._point(), old) if moved and self.pen_on else None
        return Step(pose, stroke)

    def _drive_goal(self, now_ns: int, log: Log) -> None:
        goal = self.goal
        assert goal is not None
        if goal.cancel_requested():
            log("info", "Rotation goal canceled")
            goal.canceled(self.goal_delta)
            self._end_goal()
            return
        theta = normalize_angle(goal.theta)
        remaining = normalize_angle(theta - f32(self.orient))
        self.goal_delta = normalize_angle(f32(self.goal_start_orient - self.orient))
        goal.feedback(remaining)
        if abs(normalize_angle(f32(self.orient) - theta)) < ROTATION_TOLERANCE:
            log("info", "Rotation goal completed successfully")
            goal.succeed(self.goal_delta)
            self._end_goal()
            return
        self.lin_vel_x = self.lin_vel_y = 0.0
        self.ang_vel = -1.0 if remaining < 0.0 else 1.0
        self.last_command_ns = now_ns

    def _end_goal(self) -> None:
        self.goal = None
        self.lin_vel_x = self.lin_vel_y = self.ang_vel = 0.0

    def _point(self) -> tuple[float, float]:
        return (self.x * METER_PX, self.y_down * METER_PX)

    def pixel(self) -> tuple[int, int]:
        """The pixel under the turtle (what its colour sensor reads), rounded as Qt's
        ``QPointF::toPoint`` rounds."""
        px, py = self._point()
        return (_qround(px), _qround(py))


class World:
    """The turtles by name, and the name counter of ``/spawn``."""

    def __init__(self, choose_image: Callable[[], int]) -> None:
        self.turtles: dict[str, Turtle] = {}
        self._choose_image = choose_image
        self._counter = 0

    def spawn(self, name: str, x: float, y: float, theta: float, now_ns: int) -> Turtle | None:
        """A new turtle at world ``(x, y, theta)``, named ``name`` or, when it is empty, the
        first free ``turtleN`` after the last one given; None when ``name`` is taken."""
        if not name:
            while True:
                self._counter += 1
                name = f"turtle{self._counter}"
                if name not in self.turtles:
                    break
        elif name in self.turtles:
            return None
        # Jazzy passes the position as C++ floats
        turtle = Turtle(name, f32(x), HEIGHT_M - f32(y), f32(theta), self._choose_image(), now_ns)
        self.turtles[name] = turtle
        return turtle

    def kill(self, name: str) -> Turtle | None:
        """Remove the turtle ``name``; it, or None when there is none of that name."""
        return self.turtles.pop(name, None)

    def reset(self) -> list[Turtle]:
        """Remove every turtle and start the names again at ``turtle1``; the removed ones."""
        removed = list(self.turtles.values())
        self.turtles.clear()
        self._counter = 0
        return removed


def _qround(value: float) -> int:
    """Qt's ``qRound``: half away from zero."""
    return math.floor(value + 0.5) if value >= 0 else math.ceil(value - 0.5)
