"""A robot's kinematic tree from URDF text, and the transforms a state publisher sends.

Pure logic, no transport: :func:`parse_urdf` checks the text (well-formed XML, a ``<robot>``
root, known joint types, joints naming links that exist, one tree with one root) and reads each
joint through yourdfpy; :class:`RobotModel` then answers what ``robot_state_publisher`` and
``joint_state_publisher`` need: which joints move, the fixed parent→child transforms (for
``/tf_static``) and the moving ones for given joint positions (for ``/tf``).

Like ROS's KDL parser, ``floating`` and ``planar`` joints are treated as fixed: a joint state
cannot express them.
"""

from __future__ import annotations

import io
from collections.abc import Mapping
from dataclasses import dataclass

import yourdfpy
from lxml import etree

from launchkit.errors import Location, UserError
from launchkit.stock.rotations import (
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
        urdf = yourdfpy.URDF.load(
            io.BytesIO(text.encode()), build_scene_graph=False, load_meshes=False
        )
    except Exception as exc:  # yourdfpy reports malformed values with assorted exceptions
        raise UrdfError(f"the robot description cannot be read: {exc}", Location(source)) from None
    joints = tuple(_joint(j) for j in urdf.robot.joints)
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


def _joint(joint: yourdfpy.Joint) -> Joint:
    matrix = joint.origin
    if matrix is None:
        translation: Vector = (0.0, 0.0, 0.0)
        rotation: Quaternion = (0.0, 0.0, 0.0, 1.0)
    else:
        translation = (float(matrix[0][3]), float(matrix[1][3]), float(matrix[2][3]))
        rotation = matrix_to_quaternion([[float(v) for v in row[:3]] for row in matrix[:3]])
    axis = unit(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0))
    mimic = None
    if joint.mimic is not None:
        mimic = Mimic(
            str(joint.mimic.joint),
            float(joint.mimic.multiplier if joint.mimic.multiplier is not None else 1.0),
            float(joint.mimic.offset if joint.mimic.offset is not None else 0.0),
        )
    lower = upper = None
    if joint.limit is not None and joint.type != "continuous":
        lower = None if joint.limit.lower is None else float(joint.limit.lower)
        upper = None if joint.limit.upper is None else float(joint.limit.upper)
    return Joint(
        str(joint.name),
        str(joint.type),
        str(joint.parent),
        str(joint.child),
        translation,
        rotation,
        axis,
        mimic,
        lower,
        upper,
    )
