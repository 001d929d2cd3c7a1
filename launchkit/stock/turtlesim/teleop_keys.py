"""What each key does in ``turtle_teleop_key``, as Jazzy's: pure logic, no terminal, no ROS.

Keys are read one byte at a time, so an arrow key (``ESC [ A``) counts by its last byte: ``A``
up (forward), ``B`` down (back), ``C`` right (turn clockwise), ``D`` left. The lower-case
letters around ``f`` ask for an absolute heading (``rotate_absolute``), ``f`` cancels it, ``q``
quits; every other byte is ignored.
"""

from __future__ import annotations

from dataclasses import dataclass

INSTRUCTIONS = [
    "Reading from keyboard",
    "---------------------------",
    "Use arrow keys to move the turtle.",
    "Use G|B|V|C|D|E|R|T keys to rotate to absolute orientations. 'F' to cancel a rotation.",
    "'Q' to quit.",
]

#: last byte of an arrow key -> (linear, angular) before scaling
MOVES: dict[str, tuple[float, float]] = {
    "A": (1.0, 0.0),
    "B": (-1.0, 0.0),
    "C": (0.0, -1.0),
    "D": (0.0, 1.0),
}
#: key -> the heading (radians) a rotate_absolute goal asks for, as the keyboard's layout
#: around F points (G east, T north-east, R north, ... B south-east)
HEADINGS: dict[str, float] = {
    "g": 0.0,
    "t": 0.7854,
    "r": 1.5708,
    "e": 2.3562,
    "d": 3.1416,
    "c": -2.3562,
    "v": -1.5708,
    "b": -0.7854,
}
CANCEL = "f"
QUIT = ("q", "\x03")  # Ctrl-C arrives as a byte in raw mode


@dataclass(frozen=True)
class KeyAction:
    """What a key asks for: a twist (``linear``, ``angular``), a heading, a cancel, or quit."""

    linear: float = 0.0
    angular: float = 0.0
    heading: float | None = None
    cancel: bool = False
    quit: bool = False

    @property
    def moves(self) -> bool:
        """Whether a twist is to be published."""
        return self.linear != 0.0 or self.angular != 0.0


def action_for(key: str) -> KeyAction:
    """The action of one key (a single character)."""
    if key in MOVES:
        linear, angular = MOVES[key]
        return KeyAction(linear=linear, angular=angular)
    if key in HEADINGS:
        return KeyAction(heading=HEADINGS[key])
    if key == CANCEL:
        return KeyAction(cancel=True)
    return KeyAction(quit=key in QUIT)
