"""The diff drive's kinematics, acceleration limit, configuration and odometry, alone."""

from __future__ import annotations

import math

import pytest

from launchkit.rotations import quaternion_from_yaw, yaw_of
from launchkit.stock.gazebo_ros.sim.diff_drive import (
    ENCODER,
    BaseState,
    DiffDriveConfigError,
    DiffDriveController,
    DiffDriveParams,
    wheel_geometry_warnings,
)

SEED_TAGS = {
    "odometry_frame": "odom",
    "commandTopic": "cmd_vel",
    "publish_odom": "true",
    "publish_odom_tf": "true",
    "update_rate": "15.0",
    "left_joint": "wheel_left_joint",
    "right_joint": "wheel_right_joint",
    "wheel_separation": "0.5",
    "wheel_diameter": "0.3",
    "max_wheel_acceleration": "0.7",
    "max_wheel_torque": "8",
    "robotBaseFrame": "base",
}
AT_REST = BaseState((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def test_seed_plugin_block_gives_ros2_values_and_honours_ros1_tags() -> None:
    messages: list[str] = []
    params = DiffDriveParams.from_tags(SEED_TAGS, messages.append)
    assert params.robot_base_frame == "base"  # ROS 2 gazebo_ros would say base_footprint
    assert params.command_topic == "cmd_vel"
    assert (params.wheel_separation, params.wheel_radius, params.max_wheel_torque) == (
        0.5,
        0.15,
        8.0,
    )
    assert params.update_period == pytest.approx(1 / 15)
    assert params.publish_odom and params.publish_odom_tf and not params.publish_wheel_tf
    assert any("robotBaseFrame" in m and "honoured" in m for m in messages)


def test_ros2_tag_wins_over_its_ros1_alias() -> None:
    messages: list[str] = []
    tags = dict(SEED_TAGS, robot_base_frame="chassis", wheelSeparation="9")
    params = DiffDriveParams.from_tags(tags, messages.append)
    assert params.robot_base_frame == "chassis"
    assert params.wheel_separation == 0.5
    assert any("wheelSeparation" in m and "ignored" in m for m in messages)


def test_defaults_are_gazebo_ros_defaults() -> None:
    params = DiffDriveParams.from_parameters({"left_joint": "l", "right_joint": "r"})
    assert params.robot_base_frame == "base_footprint"
    assert (params.wheel_separation, params.wheel_diameter, params.update_rate) == (
        0.34,
        0.15,
        100.0,
    )
    assert params.odometry_source == 1 and not params.publish_odom


def test_missing_joint_and_bad_number_are_clear_errors() -> None:
    with pytest.raises(DiffDriveConfigError, match="left_joint"):
        DiffDriveParams.from_tags({"right_joint": "r"})
    with pytest.raises(DiffDriveConfigError, match=r"wheel_diameter.*expected a float"):
        DiffDriveParams.from_tags(dict(SEED_TAGS, wheel_diameter="wide"))


def test_rim_speeds_follow_joint_space_convention() -> None:
    ctl = DiffDriveController(DiffDriveParams.from_tags(SEED_TAGS))
    ctl.set_command(0.5, 1.0)
    assert ctl.desired_rim_speeds() == pytest.approx((0.25, 0.75))


def test_no_acceleration_limit_sets_target_at_once() -> None:
    params = DiffDriveParams.from_tags(dict(SEED_TAGS, max_wheel_acceleration="0"))
    ctl = DiffDriveController(params)
    ctl.set_command(0.3, 0.0)
    update = ctl.update(0.1, (0.0, 0.0), AT_REST)
    assert update is not None
    assert update.command.velocities == pytest.approx(
        {"wheel_left_joint": 2.0, "wheel_right_joint": 2.0}
    )
    assert update.command.max_torque == 8.0


def test_acceleration_limit_ramps_and_rate_gate_holds_between_updates() -> None:
    ctl = DiffDriveController(DiffDriveParams.from_tags(SEED_TAGS))
    ctl.set_command(0.5, 0.0)
    first = ctl.update(1 / 15, (0.0, 0.0), AT_REST)
    assert first is not None
    # 0.7 m/s² for 1/15 s = 0.04667 m/s of rim speed, / 0.15 m radius.
    assert first.command.velocities["wheel_left_joint"] == pytest.approx(0.7 / 15 / 0.15)
    assert ctl.update(1 / 15 + 0.01, (0.0, 0.0), AT_REST) is None
    second = ctl.update(2 / 15, (0.3111, 0.3111), AT_REST)
    assert second is not None
    assert second.command.velocities["wheel_left_joint"] == pytest.approx(2 * 0.7 / 15 / 0.15)


def test_world_odometry_is_the_pose_with_twist_in_the_base_yaw_frame() -> None:
    ctl = DiffDriveController(DiffDriveParams.from_tags(SEED_TAGS))
    base = BaseState(
        (1.0, 2.0, 0.15), quaternion_from_yaw(math.pi / 2), (0.0, -0.5, 0.0), (0, 0, 0.2)
    )
    update = ctl.update(0.1, (0.0, 0.0), base)
    assert update is not None
    odom = update.odometry
    assert (odom.frame_id, odom.child_frame_id) == ("odom", "base")
    assert odom.position == (1.0, 2.0, 0.15)
    assert odom.linear[0] == pytest.approx(-0.5) and odom.linear[1] == pytest.approx(0.0, abs=1e-12)
    assert odom.angular[2] == 0.2
    assert odom.pose_covariance[0] == 1e-5 and odom.pose_covariance[35] == 1e-3
    assert odom.pose_covariance[14] == 1e12


def test_encoder_odometry_integrates_wheel_speeds() -> None:
    params = DiffDriveParams.from_tags(dict(SEED_TAGS, odometry_source=str(ENCODER)))
    ctl = DiffDriveController(params)
    # Spin in place: left back, right forward, 1 rad/s of yaw for 2 s.
    rim = 1.0 * 0.5 / 2
    wheels = (-rim / 0.15, rim / 0.15)
    update = None
    for i in range(2401):
        update = ctl.update(i / 1200, wheels, AT_REST) or update
    assert update is not None
    # 1 rad/s since t = 0, as of the last (rate-gated) update.
    assert update.odometry.stamp > 1.9
    assert yaw_of(update.odometry.orientation) == pytest.approx(update.odometry.stamp, abs=1e-6)
    assert update.odometry.angular[2] == pytest.approx(1.0)


def test_geometry_warnings_name_the_seed_inversions() -> None:
    warnings = wheel_geometry_warnings(-0.25, 0.25, (0, -1, 0), (0, -1, 0))
    assert len(warnings) == 3
    assert wheel_geometry_warnings(0.25, -0.25, (0, 1, 0), (0, 1, 0)) == []


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_a_non_finite_command_is_refused_and_the_last_one_stays(bad: float) -> None:
    ctl = DiffDriveController(
        DiffDriveParams.from_tags(dict(SEED_TAGS, max_wheel_acceleration="0"))
    )
    assert ctl.set_command(0.3, 0.0)
    assert not ctl.set_command(bad, 0.0) and not ctl.set_command(0.0, bad)
    update = ctl.update(0.1, (0.0, 0.0), AT_REST)
    assert update is not None
    assert update.command.velocities == pytest.approx(
        {"wheel_left_joint": 2.0, "wheel_right_joint": 2.0}
    )
