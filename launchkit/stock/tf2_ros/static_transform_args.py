"""``static_transform_publisher``'s command line, read as tf2_ros (Jazzy) reads it.

New style: ``--x X --y Y --z Z``, a rotation as ``--qx --qy --qz --qw`` or ``--roll --pitch
--yaw`` (radians, not both kinds), ``--frame-id`` and ``--child-frame-id``; missing values are
the identity. Old style (deprecated, with a warning): eight words ``x y z yaw pitch roll frame
child`` or nine ``x y z qx qy qz qw frame child``. Numbers are read as C's ``strtod`` reads them:
the longest number at the start (``1.5m`` is 1.5).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import NamedTuple

from launchkit.errors import UserError
from launchkit.rotations import Quaternion, Vector, rpy_to_quaternion

USAGE = (
    "usage: static_transform_publisher [--x X] [--y Y] [--z Z] [--qx QX] [--qy QY] [--qz QZ] "
    "[--qw QW] [--roll ROLL] [--pitch PITCH] [--yaw YAW] --frame-id FRAME_ID --child-frame-id "
    "CHILD_FRAME_ID\n\n"
    "A command line utility for manually sending a static transform.\n\n"
    "If no translation or orientation is provided, the identity transform will be published.\n\n"
    "The translation offsets are in meters.\n\n"
    "The rotation may be provided with roll, pitch, yaw euler angles in radians, or as a "
    "quaternion.\n\n"
    "required arguments:\n"
    "  --frame-id FRAME_ID parent frame\n"
    "  --child-frame-id CHILD_FRAME_ID child frame id\n\n"
    "optional arguments:\n"
    "  --x X                 x component of translation\n"
    "  --y Y                 y component of translation\n"
    "  --z Z                 z component of translation\n"
    "  --qx QX               x component of quaternion rotation\n"
    "  --qy QY               y component of quaternion rotation\n"
    "  --qz QZ               z component of quaternion rotation\n"
    "  --qw QW               w component of quaternion rotation\n"
    "  --roll ROLL           roll component Euler rotation\n"
    "  --pitch PITCH         pitch component Euler rotation\n"
    "  --yaw YAW             yaw component Euler rotation"
)
OLD_STYLE_WARNING = "Old-style arguments are deprecated; see --help for new-style arguments"

_NUMBER = re.compile(
    r"\s*[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)", re.IGNORECASE
)
_TRANSLATION = ("--x", "--y", "--z")
_QUATERNION = ("--qx", "--qy", "--qz", "--qw")
_EULER = ("--roll", "--pitch", "--yaw")
_FRAMES = ("--frame-id", "--child-frame-id")
_OLD_STYLE_EULER = ("x", "y", "z", "yaw", "pitch", "roll")
_OLD_STYLE_QUATERNION = ("x", "y", "z", "qx", "qy", "qz", "qw")


class StaticTransform(NamedTuple):
    """What to publish: ``translation`` and ``rotation`` of ``child`` in ``parent``."""

    translation: Vector
    rotation: Quaternion
    parent: str
    child: str


class Arguments(NamedTuple):
    """The command line read: the transform, or ``help``."""

    transform: StaticTransform | None
    help: bool


class ArgumentError(UserError):
    """A command line static_transform_publisher cannot read."""

    def __init__(self, reason: str) -> None:
        super().__init__(
            f"error parsing command line arguments: {reason}",
            expected="--frame-id FRAME_ID --child-frame-id CHILD_FRAME_ID and the optional "
            "--x/--y/--z, --qx/--qy/--qz/--qw or --roll/--pitch/--yaw; see --help",
        )


def number(text: str, name: str) -> float:
    """The number ``text`` starts with, as C's ``strtod`` reads it."""
    found = _NUMBER.match(text)
    if found is None:
        raise ArgumentError(f"Failed to parse {name} argument as float")
    return float(found.group(0))


def parse(args: list[str], warn: Callable[[str], object]) -> Arguments:
    """Read ``args`` (the program's words after the program name, ROS arguments removed);
    ``warn`` gets the deprecation warning of old-style arguments."""
    values: dict[str, float] = {}
    frames = {"--frame-id": "", "--child-frame-id": ""}
    words: list[str] = []
    wants_help = frames_given = False
    index = 0
    while index < len(args):
        word = args[index]
        if word in ("--help", "-h"):
            wants_help = True
        elif word in _TRANSLATION + _QUATERNION + _EULER + _FRAMES:
            if index == len(args) - 1:
                raise ArgumentError(f"Not enough arguments for {word}")
            index += 1
            if word in _FRAMES:
                frames[word] = args[index]
                frames_given = True
            else:
                values[word] = number(args[index], word)
        else:
            words.append(word)
        index += 1
    if wants_help:
        return Arguments(None, True)

    quaternion_given = any(flag in values for flag in _QUATERNION)
    euler_given = any(flag in values for flag in _EULER)
    if quaternion_given and euler_given:
        raise ArgumentError("Cannot specify both quaternion and Euler rotations")
    if len(words) in (8, 9):
        warn(OLD_STYLE_WARNING)
        if any(flag in values for flag in _TRANSLATION + _QUATERNION) or frames_given:
            raise ArgumentError("Cannot specify both new-style (flags) and old-style (arguments)")
        names = _OLD_STYLE_EULER if len(words) == 8 else _OLD_STYLE_QUATERNION
        read = {name: number(word, name) for name, word in zip(names, words, strict=False)}
        x, y, z = read["x"], read["y"], read["z"]
        if len(words) == 8:
            rotation = rpy_to_quaternion(read["roll"], read["pitch"], read["yaw"])
        else:
            rotation = (read["qx"], read["qy"], read["qz"], read["qw"])
        frames = {"--frame-id": words[-2], "--child-frame-id": words[-1]}
    else:
        if words:
            raise ArgumentError("Extra unparsed arguments on command-line")
        x, y, z = (values.get(flag, 0.0) for flag in _TRANSLATION)
        if euler_given:
            rotation = rpy_to_quaternion(*(values.get(flag, 0.0) for flag in _EULER))
        else:
            rotation = (
                values.get("--qx", 0.0),
                values.get("--qy", 0.0),
                values.get("--qz", 0.0),
                values.get("--qw", 1.0),
            )
    if not frames["--frame-id"]:
        raise ArgumentError("Frame id must not be empty")
    if not frames["--child-frame-id"]:
        raise ArgumentError("Child frame id must not be empty")
    transform = StaticTransform(
        (x, y, z), rotation, frames["--frame-id"], frames["--child-frame-id"]
    )
    return Arguments(transform, False)
