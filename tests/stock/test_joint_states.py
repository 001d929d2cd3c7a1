"""joint_state_publisher's state: defaults, zeros, merged sources, mimic joints (no transport)."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.stock.joint_state_publisher.state import JointStateMerger
from launchkit.stock.urdf import parse_urdf

SEED = parse_urdf((Path(__file__).parents[2] / "urdf" / "three_wheeled_robot.urdf").read_text())

GRIPPER = parse_urdf(
    """<robot name="gripper">
  <link name="palm"/><link name="lift"/><link name="left"/><link name="right"/><link name="cam"/>
  <joint name="lift_joint" type="prismatic"><parent link="palm"/><child link="lift"/>
    <limit lower="0.1" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="left_joint" type="revolute"><parent link="lift"/><child link="left"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="right_joint" type="revolute"><parent link="lift"/><child link="right"/>
    <mimic joint="left_joint" multiplier="-1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="palm"/><child link="cam"/></joint>
</robot>"""
)


def test_seed_joints_start_at_zero() -> None:
    state = JointStateMerger(SEED).current()
    assert state.name == ["wheel_right_joint", "wheel_left_joint", "caster_joint"]
    assert state.position == [0.0, 0.0, 0.0]


def test_zero_outside_the_limits_rests_mid_range_and_zeros_override() -> None:
    assert JointStateMerger(GRIPPER).current().position == pytest.approx([0.3, 0.0, 0.0])
    state = JointStateMerger(GRIPPER, {"lift_joint": 0.2, "left_joint": 0.4}).current()
    assert state.name == ["lift_joint", "left_joint", "right_joint"]
    assert state.position == pytest.approx([0.2, 0.4, -0.4])


def test_sources_overwrite_only_the_joints_they_name() -> None:
    merger = JointStateMerger(SEED, {"caster_joint": 1.5})
    merger.merge(["wheel_left_joint", "elsewhere_joint"], [2.0, 9.0], [0.5, 1.0])
    state = merger.current()
    assert state.position == [0.0, 2.0, 1.5]
    assert state.velocity == [0.0, 0.5, 0.0]
    merger.merge(["wheel_left_joint"], [3.0])
    assert merger.current().position == [0.0, 3.0, 1.5]


def test_mimic_joints_follow_their_leader_from_a_source() -> None:
    merger = JointStateMerger(GRIPPER)
    merger.merge(["left_joint", "right_joint"], [0.7, 5.0], [0.1, 9.0])
    state = merger.current()
    assert state.position == pytest.approx([0.3, 0.7, -0.7])
    assert state.velocity == pytest.approx([0.0, 0.1, -0.1])


def test_zeros_for_a_joint_that_does_not_move_is_refused() -> None:
    with pytest.raises(ValueError, match="cam_joint"):
        JointStateMerger(GRIPPER, {"cam_joint": 1.0})
