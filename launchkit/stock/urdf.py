"""A robot's kinematic tree from URDF text, and the transforms a state publisher sends.

Pure logic, no transport: :func:`parse_urdf` checks the text (well-formed XML, a ``<robot>``
root, known joint types, joints naming links that exist, one tree with one root) and reads each
joint's origin, axis, mimic and limits; :class:`RobotModel` then answers what
``robot_state_publisher`` and ``joint_state_publisher`` need: which joints move, the fixed
parent→child transforms (for ``/tf_static``) and the moving ones for given joint positions (for
``/tf``).

Like ROS's KDL parser, ``floating`` and ``planar`` joints are treated as fixed: a joint state
cannot express them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from lxml import etree

from launchkit.errors import Location, UserError
from launchkit.rotations import (
    Quaternion,
    Vector,
    axis_angle,
    matrix_to_quaternion,
    quaternion_multiply,
    rotate,
    unit,
)

#: Joint types whose position comes from ``/joint_states``.
MOVING_TYPES = frozenset({"revolute", "continuous", "prismatic"})
#: Joint types published once on ``/tf_static``.
FIXED_TYPES = frozenset({"fixed", "floating", "planar"})


class UrdfError(UserError):
    """The robot description is not a usable URDF (exit status 2)."""


@dataclass(frozen=True)
class Transform:
    """The pose of frame ``child`` in frame ``parent``: a translation, then a rotation."""

    parent: str
    child: str
    translation: Vector
    rotation: Quaternion


@dataclass(frozen=True)
class Mimic:
    """A joint that follows another: ``position = multiplier * other + offset``."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class Joint:
    """One URDF joint: its frames, its fixed origin and the axis it moves along or about."""

    name: str
    type: str
    parent: str
    child: str
    origin_translation: Vector
    origin_rotation: Quaternion
    axis: Vector
    mimic: Mimic | None = None
    lower: float | None = None
    upper: float | None = None

    @property
    def moving(self) -> bool:
        """True when the joint's position comes from a joint state."""
        return self.type in MOVING_TYPES

    def transform(self, position: float = 0.0, frame_prefix: str = "") -> Transform:
        """The child frame's pose in the parent frame with the joint at ``position``."""
        translation = self.origin_translation
        rotation = self.origin_rotation
        if self.type in ("revolute", "continuous"):
            rotation = quaternion_multiply(rotation, axis_angle(self.axis, position))
        elif self.type == "prismatic":
            ax, ay, az = self.axis
            step = rotate(rotation, (ax * position, ay * position, az * position))
            tx, ty, tz = translation
            translation = (tx + step[0], ty + step[1], tz + step[2])
        prefix = frame_prefix
        return Transform(prefix + self.parent, prefix + self.child, translation, rotation)


@dataclass(frozen=True)
class RobotModel:
    """A checked URDF: its name, root link and joints in document order."""

    name: str
    root: str
    joints: tuple[Joint, ...]

    @property
    def moving_joints(self) -> list[Joint]:
        """Joints whose positions come from ``/joint_states`` (mimic joints included)."""
        return [j for j in self.joints if j.moving]

    @property
    def free_joints(self) -> list[Joint]:
        """Moving joints that do not mimic another: the ones a joint state publisher drives."""
        return [j for j in self.joints if j.moving and j.mimic is None]

    def fixed_transforms(self, frame_prefix: str = "") -> list[Transform]:
        """Transforms of every fixed joint, for ``/tf_static``."""
        return [j.transform(0.0, frame_prefix) for j in self.joints if not j.moving]

    def moving_transforms(
        self, positions: Mapping[str, float], frame_prefix: str = ""
    ) -> list[Transform]:
        """Transforms of the moving joints whose position is known (directly or by mimic)."""
        out = []
        for joint in self.moving_joints:
            position = self.position_of(joint, positions)
            if position is not None:
                out.append(joint.transform(position, frame_prefix))
        return out

    def position_of(self, joint: Joint, positions: Mapping[str, float]) -> float | None:
        """The position of ``joint``: given, or derived from the joint it mimics; else None."""
        if joint.mimic is not None:
            leader = positions.get(joint.mimic.joint)
            if leader is None:
                return None
            return joint.mimic.multiplier * leader + joint.mimic.offset
        return positions.get(joint.name)


# -- parsing ---------------------------------------------------------------------------------


def parse_urdf(text: str, source: str = "robot_description") -> RobotModel:
    """Check URDF ``text`` and build its model; :class:`UrdfError` names the first problem.

    ``source`` names where the text came from, for the error's location.
    """
    if not text.strip():
        raise UrdfError("the robot description is empty", Location(source), expected="URDF XML")
    try:
        root = etree.fromstring(text.encode(), parser=etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError as exc:
        line, col = exc.position if exc.position else (0, 0)
        raise UrdfError(
            f"the robot description is not well-formed XML: {exc.msg}",
            Location(source, line, col + 1 if line else 0),
            expected="URDF XML",
        ) from None
    if root.tag != "robot":
        raise UrdfError(
            f"the root element is <{root.tag}>",
            _at(source, root),
            expected="<robot name=...>",
        )
    _check_tree(root, source)
    try:
        joints = tuple(_joint(element) for element in root.iterfind("joint"))
    except ValueError as exc:
        raise UrdfError(f"the robot description cannot be read: {exc}", Location(source)) from None
    return RobotModel(str(root.get("name", "")), _root_link(root, source), joints)


def _check_tree(root: etree._Element, source: str) -> None:
    links = {}
    for element in root.iterfind("link"):
        name = element.get("name")
        if not name:
            raise UrdfError("a <link> has no name", _at(source, element), expected='name="..."')
        links[name] = element
    if not links:
        raise UrdfError("the robot has no <link>", _at(source, root), expected="at least one link")
    parent_of: dict[str, str] = {}
    for joint in root.iterfind("joint"):
        name = joint.get("name")
        kind = joint.get("type")
        if not name:
            raise UrdfError("a <joint> has no name", _at(source, joint), expected='name="..."')
        if kind not in MOVING_TYPES | FIXED_TYPES:
            raise UrdfError(
                f"joint {name!r} has type {kind!r}",
                _at(source, joint),
                expected="one of " + ", ".join(sorted(MOVING_TYPES | FIXED_TYPES)),
            )
        ends: dict[str, str] = {}
        for end in ("parent", "child"):
            end_element = joint.find(end)
            link = end_element.get("link") if end_element is not None else None
            if end_element is None or not link:
                raise UrdfError(
                    f"joint {name!r} has no {end} link",
                    _at(source, joint),
                    expected=f'<{end} link="..."/>',
                )
            if link not in links:
                raise UrdfError(
                    f"joint {name!r} names {end} link {link!r}, which is not defined",
                    _at(source, end_element),
                    expected="one of " + ", ".join(sorted(links)),
                )
            ends[end] = link
        if ends["child"] in parent_of:
            raise UrdfError(
                f"link {ends['child']!r} is the child of two joints",
                _at(source, joint),
                expected="a tree: one parent joint per link",
            )
        parent_of[ends["child"]] = ends["parent"]
    _root_link(root, source)  # exactly one root
    for start in parent_of:  # no cycles: every chain of parents ends at the root
        seen = {start}
        current = start
        while current in parent_of:
            current = parent_of[current]
            if current in seen:
                raise UrdfError(
                    f"the joints form a loop through link {current!r}", Location(source)
                )
            seen.add(current)


def _root_link(root: etree._Element, source: str) -> str:
    links = [str(link.get("name")) for link in root.iterfind("link")]
    children = {str(c.get("link")) for c in root.iterfind("joint/child")}
    roots = [name for name in links if name not in children]
    if len(roots) != 1:
        raise UrdfError(
            f"the robot has {len(roots)} root links ({', '.join(roots) or 'none'})",
            _at(source, root),
            expected="one tree with exactly one root link",
        )
    return roots[0]


def _at(source: str, element: etree._Element) -> Location:
    line = element.sourceline
    return Location(source, line if isinstance(line, int) else 0)


def _joint(element: etree._Element) -> Joint:
    """One checked ``<joint>`` (its name, type and links exist): origin, axis, mimic, limits.

    Read here rather than through yourdfpy, whose import (trimesh, scipy) took most of a state
    publisher's start-up; a malformed number raises ValueError.
    """
    name = str(element.get("name"))
    origin = element.find("origin")
    translation: Vector = (0.0, 0.0, 0.0)
    rotation: Quaternion = (0.0, 0.0, 0.0, 1.0)
    if origin is not None:
        translation = _vector(origin.get("xyz"), (0.0, 0.0, 0.0), name, "origin xyz")
        roll, pitch, yaw = _vector(origin.get("rpy"), (0.0, 0.0, 0.0), name, "origin rpy")
        rotation = matrix_to_quaternion(_rpy_matrix(roll, pitch, yaw))
    axis_element = element.find("axis")
    axis_text = None if axis_element is None else axis_element.get("xyz")
    axis = unit(_vector(axis_text, (1.0, 0.0, 0.0), name, "axis xyz"))
    mimic = None
    mimic_element = element.find("mimic")
    if mimic_element is not None:
        mimic = Mimic(
            str(mimic_element.get("joint")),
            _number(mimic_element.get("multiplier"), 1.0, name, "mimic multiplier"),
            _number(mimic_element.get("offset"), 0.0, name, "mimic offset"),
        )
    kind = str(element.get("type"))
    lower = upper = None
    limit = element.find("limit")
    if limit is not None and kind != "continuous":
        lower = _number(limit.get("lower"), None, name, "limit lower")
        upper = _number(limit.get("upper"), None, name, "limit upper")
    return Joint(
        name,
        kind,
        str(_end(element, "parent")),
        str(_end(element, "child")),
        translation,
        rotation,
        axis,
        mimic,
        lower,
        upper,
    )


def _end(joint: etree._Element, end: str) -> str | None:
    element = joint.find(end)
    return None if element is None else element.get("link")


def _vector(text: str | None, default: Vector, joint: str, what: str) -> Vector:
    if text is None:
        return default
    values = text.split()
    if len(values) != 3:
        raise ValueError(f"joint {joint!r}: {what} {text!r} is not three numbers")
    x, y, z = (_number(v, 0.0, joint, what) for v in values)
    return (x, y, z)


def _number(text: str | None, default: float | None, joint: str, what: str) -> Any:
    if text is None:
        return default
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"joint {joint!r}: {what} {text!r} is not a number") from None


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> list[list[float]]:
    """URDF's fixed-axis roll, pitch, yaw as the rotation matrix Rz(yaw)·Ry(pitch)·Rx(roll)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
