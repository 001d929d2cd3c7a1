"""Where launchkit's simulator differs from gazebo_ros for the seed's sake: the lidar's default
topic and ``/joint_states`` for a model without a joint state plugin; and the joint state plugin
itself."""

from __future__ import annotations

import pytest

from launchkit.stock.gazebo_ros.sim.engine import Simulation, SimulationError
from launchkit.stock.gazebo_ros.sim.plugins import PluginDefaults, load_plugins

SERVER_DEFAULTS = PluginDefaults(ray_topic="scan", joint_state_rate=50.0)
JOINT_STATE_BLOCK = """
    <gazebo>
        <plugin name="joint_states" filename="libgazebo_ros_joint_state_publisher.so">
            <ros><namespace>/robot</namespace></ros>
            <update_rate>20</update_rate>
            {joints}
        </plugin>
    </gazebo>
</robot>"""


def with_block(urdf: str, block: str) -> str:
    """The seed URDF with ``block`` (which closes ``</robot>``) appended."""
    return urdf.replace("</robot>", block)


def test_gazebo_ros_names_are_kept_by_default(empty_sim: Simulation, seed_urdf: str) -> None:
    entity = empty_sim.spawn("robot", seed_urdf)
    plugins = load_plugins(empty_sim, entity, lambda _m: None)
    assert plugins.lidars[0].config.topic == "/gazebo_lidar/out"
    assert plugins.joint_states == []


def test_server_defaults_give_scan_and_joint_states(empty_sim: Simulation, seed_urdf: str) -> None:
    logged: list[str] = []
    entity = empty_sim.spawn("robot", seed_urdf)
    plugins = load_plugins(empty_sim, entity, logged.append, SERVER_DEFAULTS)
    assert plugins.lidars[0].config.topic == "/scan"
    assert any("gazebo_ros would use /gazebo_lidar/out" in m for m in logged), logged
    (output,) = plugins.joint_states
    assert (output.topic, output.rate, output.implicit) == ("/joint_states", 50.0, True)
    assert set(output.joints) == {"wheel_left_joint", "wheel_right_joint", "caster_joint"}


def test_an_explicit_remapping_wins(empty_sim: Simulation, seed_urdf: str) -> None:
    remapped = seed_urdf.replace(
        "<output_type>sensor_msgs/LaserScan</output_type>",
        "<ros><remapping>~/out:=front/laser</remapping></ros>"
        "<output_type>sensor_msgs/LaserScan</output_type>",
    )
    assert remapped != seed_urdf
    entity = empty_sim.spawn("robot", remapped)
    plugins = load_plugins(empty_sim, entity, lambda _m: None, SERVER_DEFAULTS)
    assert plugins.lidars[0].config.topic == "/front/laser"


def test_a_joint_state_plugin_replaces_the_implicit_stream(
    empty_sim: Simulation, seed_urdf: str
) -> None:
    joints = "<joint_name>wheel_left_joint</joint_name><joint_name>wheel_right_joint</joint_name>"
    entity = empty_sim.spawn(
        "robot", with_block(seed_urdf, JOINT_STATE_BLOCK.format(joints=joints))
    )
    plugins = load_plugins(empty_sim, entity, lambda _m: None, SERVER_DEFAULTS)
    (output,) = plugins.joint_states
    assert output.topic == "/robot/joint_states" and output.rate == 20.0
    assert output.joints == ("wheel_left_joint", "wheel_right_joint")
    assert not output.implicit


@pytest.mark.parametrize(
    ("joints", "expected"),
    [
        ("", "no <joint_name>"),
        ("<joint_name>lidar_joint</joint_name>", "'lidar_joint' is not a movable joint"),
    ],
)
def test_a_bad_joint_state_plugin_is_a_clear_error(
    empty_sim: Simulation, seed_urdf: str, joints: str, expected: str
) -> None:
    entity = empty_sim.spawn(
        "robot", with_block(seed_urdf, JOINT_STATE_BLOCK.format(joints=joints))
    )
    with pytest.raises(SimulationError, match=expected):
        load_plugins(empty_sim, entity, lambda _m: None, SERVER_DEFAULTS)


def test_the_state_stream_runs_at_the_plugins_common_rate(
    empty_sim: Simulation, seed_urdf: str
) -> None:
    entity = empty_sim.spawn("robot", seed_urdf)
    plugins = load_plugins(empty_sim, entity, lambda _m: None)
    assert plugins.state_rate(120.0) == 30.0  # the drive's 15 Hz and the camera's 30 Hz
    assert plugins.state_rate(20.0) == 20.0
    odd = seed_urdf.replace("<update_rate>15.0</update_rate>", "<update_rate>12.5</update_rate>")
    entity = empty_sim.spawn("odd", odd)
    assert load_plugins(empty_sim, entity, lambda _m: None).state_rate(120.0) == 120.0
