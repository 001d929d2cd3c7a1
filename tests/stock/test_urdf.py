"""URDF -> transforms, checked against yourdfpy's own forward kinematics (no transport)."""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from launchkit.rotations import matrix_to_quaternion, rotate, rpy_to_quaternion
from launchkit.stock.urdf import Transform, UrdfError, parse_urdf

SEED = (Path(__file__).parents[2] / "urdf" / "three_wheeled_robot.urdf").read_text()

ARM = """<robot name="arm">
  <link name="base"/><link name="upper"/><link name="slider"/><link name="finger"/>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.5" rpy="0.3 -0.2 0.1"/><axis xyz="0 1 1"/>
    <parent link="base"/><child link="upper"/><limit lower="-1" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="rail" type="prismatic">
    <origin xyz="0.1 0 0.2" rpy="0 1.2 0"/><axis xyz="1 0 0"/>
    <parent link="upper"/><child link="slider"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/>
  </joint>
  <joint name="finger_joint" type="revolute">
    <mimic joint="shoulder" multiplier="-2" offset="0.1"/><axis xyz="0 0 1"/>
    <parent link="slider"/><child link="finger"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>"""


def _matrix(t: Transform) -> np.ndarray:
    x, y, z, w = t.rotation
    m = np.eye(4)
    m[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    m[:3, 3] = t.translation
    return m


def _reference(text: str, cfg: dict[str, float]) -> Any:
    # imported here: yourdfpy brings trimesh and scipy (about a second), which every xdist
    # worker would otherwise pay while collecting the suite
    import yourdfpy

    urdf = yourdfpy.URDF.load(io.StringIO(text), load_meshes=False)
    urdf.update_cfg(cfg)
    return urdf


def test_seed_joints_split_into_moving_and_fixed() -> None:
    model = parse_urdf(SEED)
    assert model.name == "three_wheeled_robot"
    assert model.root == "base"
    assert [j.name for j in model.free_joints] == [
        "wheel_right_joint",
        "wheel_left_joint",
        "caster_joint",
    ]
    fixed = model.fixed_transforms()
    assert [(t.parent, t.child) for t in fixed] == [("base", "camera"), ("base", "lidar")]


def test_seed_lidar_transform_matches_its_origin_tag() -> None:
    lidar = parse_urdf(SEED).fixed_transforms()[1]
    assert lidar.translation == pytest.approx((-0.285, 0.0, 0.075))
    assert lidar.rotation == pytest.approx((0.0, 0.0, math.sin(0.785), math.cos(0.785)))


def test_seed_wheel_transforms_match_yourdfpy_forward_kinematics() -> None:
    positions = {"wheel_right_joint": 0.7, "wheel_left_joint": -2.5, "caster_joint": 3.0}
    reference = _reference(SEED, positions)
    for t in parse_urdf(SEED).moving_transforms(positions):
        expected = reference.get_transform(t.child, t.parent)
        np.testing.assert_allclose(_matrix(t), expected, atol=1e-9)


def test_prismatic_and_mimic_joints_match_yourdfpy() -> None:
    model = parse_urdf(ARM)
    positions = {"shoulder": 0.8, "rail": 0.25}
    assert [j.name for j in model.free_joints] == ["shoulder", "rail"]
    reference = _reference(ARM, {**positions, "finger_joint": -2 * 0.8 + 0.1})
    transforms = model.moving_transforms(positions)
    assert [t.child for t in transforms] == ["upper", "slider", "finger"]
    for t in transforms:
        np.testing.assert_allclose(
            _matrix(t), reference.get_transform(t.child, t.parent), atol=1e-9
        )


def test_joint_without_a_known_position_is_left_out() -> None:
    transforms = parse_urdf(ARM).moving_transforms({"rail": 0.1})
    assert [t.child for t in transforms] == ["slider"]


def test_frame_prefix_applies_to_both_frames() -> None:
    t = parse_urdf(SEED).fixed_transforms("robot1/")[0]
    assert (t.parent, t.child) == ("robot1/base", "robot1/camera")


def test_rotation_helpers_agree() -> None:
    q = rpy_to_quaternion(0.3, -0.2, 0.1)
    m = _matrix(Transform("a", "b", (0.0, 0.0, 0.0), q))
    assert matrix_to_quaternion(m[:3, :3].tolist()) == pytest.approx(q)
    np.testing.assert_allclose(rotate(q, (1.0, 2.0, 3.0)), m[:3, :3] @ [1.0, 2.0, 3.0])


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "the robot description is empty"),
        ("<robot name='x'><link name='a'>", "not well-formed XML"),
        ("<model/>", "the root element is <model>"),
        ("<robot name='x'/>", "the robot has no <link>"),
        (
            "<robot name='x'><link name='a'/><joint name='j' type='hinge'>"
            "<parent link='a'/><child link='b'/></joint></robot>",
            "joint 'j' has type 'hinge'",
        ),
        (
            "<robot name='x'><link name='a'/><joint name='j' type='fixed'>"
            "<parent link='a'/><child link='b'/></joint></robot>",
            "names child link 'b', which is not defined",
        ),
        (
            "<robot name='x'><link name='a'/><link name='b'/><joint name='j' type='fixed'>"
            "<parent link='a'/><child link='b'/><origin xyz='1 2'/></joint></robot>",
            "joint 'j': origin xyz '1 2' is not three numbers",
        ),
        (
            "<robot name='x'><link name='a'/><link name='b'/><joint name='j' type='revolute'>"
            "<parent link='a'/><child link='b'/><limit lower='low'/></joint></robot>",
            "joint 'j': limit lower 'low' is not a number",
        ),
        ("<robot name='x'><link name='a'/><link name='b'/></robot>", "2 root links (a, b)"),
        (
            "<robot name='x'><link name='a'/><link name='b'/><link name='c'/>"
            "<joint name='j1' type='fixed'><parent link='a'/><child link='c'/></joint>"
            "<joint name='j2' type='fixed'><parent link='b'/><child link='c'/></joint></robot>",
            "link 'c' is the child of two joints",
        ),
    ],
)
def test_bad_descriptions_give_one_line_errors(text: str, message: str) -> None:
    with pytest.raises(UrdfError) as caught:
        parse_urdf(text, source="robot_description")
    formatted = caught.value.format()
    assert message in formatted
    assert formatted.startswith("robot_description")
    assert "\n" not in formatted
    assert caught.value.exit_status == 2
