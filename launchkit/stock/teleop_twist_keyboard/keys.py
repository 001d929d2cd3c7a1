"""What each key does in ``teleop_twist_keyboard``: the key map, the speed controls, the banner.

Pure logic, no terminal and no transport: :class:`Teleop` takes one key at a time and answers
the velocity to publish, the lines to print and whether to quit, as the original node does.
"""

from __future__ import annotations

from dataclasses import dataclass, field

BANNER = """
This node takes keypresses from the keyboard and publishes them
as Twist/TwistStamped messages. It works best with a US keyboard layout.
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For Holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""

#: key -> (x, y, z, yaw) directions, multiplied by the current speed and turn.
MOVE_KEYS: dict[str, tuple[int, int, int, int]] = {
    "i": (1, 0, 0, 0),
    "o": (1, 0, 0, -1),
    "j": (0, 0, 0, 1),
    "l": (0, 0, 0, -1),
    "u": (1, 0, 0, 1),
    ",": (-1, 0, 0, 0),
    ".": (-1, 0, 0, 1),
    "m": (-1, 0, 0, -1),
    # shift: strafe instead of turning
    "O": (1, -1, 0, 0),
    "I": (1, 0, 0, 0),
    "J": (0, 1, 0, 0),
    "L": (0, -1, 0, 0),
    "U": (1, 1, 0, 0),
    "<": (-1, 0, 0, 0),
    ">": (-1, -1, 0, 0),
    "M": (-1, 1, 0, 0),
    "t": (0, 0, 1, 0),
    "b": (0, 0, -1, 0),
}

#: key -> (linear factor, angular factor).
SPEED_KEYS: dict[str, tuple[float, float]] = {
    "q": (1.1, 1.1),
    "z": (0.9, 0.9),
    "w": (1.1, 1.0),
    "x": (0.9, 1.0),
    "e": (1.0, 1.1),
    "c": (1.0, 0.9),
}

CTRL_C = "\x03"
#: The banner is shown again after this many speed changes, so it never scrolls out of sight.
BANNER_EVERY = 15


def speed_line(speed: float, turn: float) -> str:
    """The status line printed at start and after every speed change."""
    return f"currently:\tspeed {speed:.2f}\tturn {turn:.2f} "


@dataclass(frozen=True)
class Velocity:
    """What to publish: linear x, y, z and angular z."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    yaw: float = 0.0


@dataclass
class Outcome:
    """The result of one key: the velocity to publish, lines to print, whether to quit."""

    velocity: Velocity
    lines: list[str] = field(default_factory=list)
    quit: bool = False


@dataclass
class Teleop:
    """The keyboard state machine: current speeds and the direction last asked for."""

    speed: float = 0.5
    turn: float = 1.0
    speed_limit: float = 1000.0
    turn_limit: float = 1000.0
    direction: tuple[int, int, int, int] = (0, 0, 0, 0)
    _speed_changes: int = 0

    def start_lines(self) -> list[str]:
        """What the node prints when it starts."""
        return [BANNER, speed_line(self.speed, self.turn)]

    def press(self, key: str) -> Outcome:
        """Apply one key; every key, even a speed change, yields a velocity to publish."""
        lines: list[str] = []
        quit_ = False
        if key in MOVE_KEYS:
            self.direction = MOVE_KEYS[key]
        elif key in SPEED_KEYS:
            linear, angular = SPEED_KEYS[key]
            self.speed = min(self.speed_limit, self.speed * linear)
            self.turn = min(self.turn_limit, self.turn * angular)
            if self.speed == self.speed_limit:
                lines.append("Linear speed limit reached!")
            if self.turn == self.turn_limit:
                lines.append("Angular speed limit reached!")
            lines.append(speed_line(self.speed, self.turn))
            if self._speed_changes == BANNER_EVERY - 1:
                lines.append(BANNER)
            self._speed_changes = (self._speed_changes + 1) % BANNER_EVERY
        else:
            self.direction = (0, 0, 0, 0)
            quit_ = key == CTRL_C
        x, y, z, yaw = self.direction
        velocity = Velocity(x * self.speed, y * self.speed, z * self.speed, yaw * self.turn)
        return Outcome(velocity, lines, quit_)
