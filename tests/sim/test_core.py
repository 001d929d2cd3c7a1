"""The simulation core: spawning, driving against PyBullet's ground truth, sensors, determinism."""

from __future__ import annotations

import dataclasses
import hashlib
import math
import struct
from pathlib import Path

import pytest

from launchkit.rotations import yaw_of
from launchkit.stock.gazebo_ros.sim.diff_drive import DiffDriveController
from launchkit.stock.gazebo_ros.sim.engine import Entity, Simulation, SimulationError
from launchkit.stock.gazebo_ros.sim.model import ModelError
from launchkit.stock.gazebo_ros.sim.plugins import EntityPlugins, load_plugins
from launchkit.stock.gazebo_ros.sim.sensors import Camera
from launchkit.stock.gazebo_ros.sim.world import load_world, resolve_world


def spawn_seed(sim: Simulation, urdf: str, name: str = "robot") -> tuple[Entity, EntityPlugins]:
    entity = sim.spawn(name, urdf, (0, 0, 0.151, 0, 0, 0))
    plugins = load_plugins(sim, entity, lambda _m: None)
    sim.step(240)  # settle for 1 s
    return entity, plugins


def drive(
    sim: Simulation, entity: Entity, plugins: EntityPlugins, v: float, w: float, seconds: float
) -> DiffDriveController:
    """Run the diff drive in-process every step, commanding (v, w) for ``seconds`` of sim time."""
    _, params = plugins.diff_drives[0]
    ctl = DiffDriveController(params, start_time=sim.time)
    ctl.set_command(v, w)
    for _ in range(round(seconds / sim.time_step)):
        joints = sim.joint_states(entity)
        wheels = (joints[params.left_joint][1], joints[params.right_joint][1])
        update = ctl.update(sim.time, wheels, sim.base_state(entity))
        if update is not None:
            sim.set_joint_velocities(entity, update.command.velocities, update.command.max_torque)
        sim.step()
    return ctl


def test_seed_robot_spawns_and_rests_on_its_wheels(empty_sim: Simulation, seed_urdf: str) -> None:
    entity, plugins = spawn_seed(empty_sim, seed_urdf)
    base = empty_sim.base_state(entity)
    assert base.position[2] == pytest.approx(0.1506, abs=2e-3)
    assert set(entity.movable_joints) == {"wheel_right_joint", "wheel_left_joint", "caster_joint"}
    assert len(plugins.diff_drives) == 1 and len(plugins.lidars) == 1 and len(plugins.cameras) == 1


def test_spawn_into_the_ground_is_lifted(empty_sim: Simulation, seed_urdf: str) -> None:
    messages: list[str] = []
    empty_sim.log = messages.append
    entity = empty_sim.spawn("robot", seed_urdf)  # z = 0, spawn_entity.py's default
    assert empty_sim.base_state(entity).position[2] == pytest.approx(0.15, abs=5e-3)
    assert any("into the ground" in m for m in messages)


def test_spawn_errors_and_delete(empty_sim: Simulation, seed_urdf: str) -> None:
    empty_sim.spawn("robot", seed_urdf)
    with pytest.raises(SimulationError, match="already exists"):
        empty_sim.spawn("robot", seed_urdf)
    with pytest.raises(SimulationError, match="not valid XML"):
        empty_sim.spawn("other", "<robot><link")
    with pytest.raises(SimulationError, match="expected <robot>"):
        empty_sim.spawn("other", "<sdf/>")
    empty_sim.delete("robot")
    assert empty_sim.entities == {}
    with pytest.raises(SimulationError, match="does not exist"):
        empty_sim.delete("robot")


def test_materials_colour_the_links(empty_sim: Simulation, seed_urdf: str) -> None:
    entity = empty_sim.spawn("robot", seed_urdf)
    colours = {
        row[1]: tuple(round(c, 2) for c in row[7])
        for row in empty_sim.p.getVisualShapeData(entity.body, physicsClientId=empty_sim.client)
    }
    assert colours[entity.links["wheel_left_link"]] == (0.53, 0.81, 0.92, 1.0)  # Gazebo/SkyBlue
    assert colours[entity.links["camera"]] == (1.0, 0.0, 0.0, 1.0)  # Gazebo/Red


def test_forward_command_drives_the_expected_distance_like_gazebo(
    empty_sim: Simulation, seed_urdf: str
) -> None:
    entity, plugins = spawn_seed(empty_sim, seed_urdf)
    start = empty_sim.base_state(entity)
    drive(empty_sim, entity, plugins, 0.5, 0.0, 5.0)
    end = empty_sim.base_state(entity)
    # 0.5 m/s with a 0.7 m/s² ramp: 2.5 - 0.179 = 2.32 m; the seed's wheel axes make it go -x.
    dx, dy = end.position[0] - start.position[0], end.position[1] - start.position[1]
    assert dx == pytest.approx(-2.32, abs=0.08)
    assert abs(dy) < 0.05


def test_world_odometry_agrees_with_ground_truth(empty_sim: Simulation, seed_urdf: str) -> None:
    entity, plugins = spawn_seed(empty_sim, seed_urdf)
    ctl = drive(empty_sim, entity, plugins, 0.4, 0.3, 3.0)
    truth = empty_sim.base_state(entity)
    update = ctl.update(empty_sim.time + 1.0, (0.0, 0.0), truth)
    assert update is not None
    assert update.odometry.position == pytest.approx(truth.position)
    assert update.odometry.child_frame_id == "base"


def test_positive_yaw_command_turns_counter_clockwise(
    empty_sim: Simulation, seed_urdf: str
) -> None:
    entity, plugins = spawn_seed(empty_sim, seed_urdf)
    before = yaw_of(empty_sim.base_state(entity).orientation)
    drive(empty_sim, entity, plugins, 0.0, 1.0, 1.0)
    after = yaw_of(empty_sim.base_state(entity).orientation)
    turned = math.atan2(math.sin(after - before), math.cos(after - before))
    # A 0.7 m/s² rim ramp to 0.25 m/s takes 0.36 s: about 0.82 rad in the first second.
    assert 0.6 < turned < 1.0


def test_lidar_sees_the_shipped_worlds_obstacle(obstacle_sim: Simulation, seed_urdf: str) -> None:
    _entity, plugins = spawn_seed(obstacle_sim, seed_urdf)
    lidar = plugins.lidars[0]
    assert lidar.config.topic == "/gazebo_lidar/out" and lidar.config.frame_id == "lidar"
    assert lidar.config.angle_increment == pytest.approx(0.0087465, abs=1e-6)
    ranges = lidar.scan()
    assert len(ranges) == 360
    # Ray 180 points along base -x; the box's near face is at x = -2.25, the lidar at x = -0.285.
    assert ranges[180] == pytest.approx(2.25 - 0.285, abs=0.03)
    assert math.isinf(ranges[0]) and ranges[0] > 0  # toward +y: nothing within 3.5 m


def test_lidar_in_the_empty_world_sees_nothing(empty_sim: Simulation, seed_urdf: str) -> None:
    _, plugins = spawn_seed(empty_sim, seed_urdf)
    assert all(math.isinf(r) and r > 0 for r in plugins.lidars[0].scan())


def _small_camera(urdf: str) -> str:
    return urdf.replace("<width>800</width>", "<width>64</width>").replace(
        "<height>800</height>", "<height>48</height>"
    )


def _red_fraction(image: bytes) -> float:
    pixels = [image[i : i + 3] for i in range(0, len(image), 3)]
    return sum(1 for r, g, b in pixels if r > 100 and r > 2 * g and r > 2 * b) / len(pixels)


def test_camera_sees_the_box_ahead(obstacle_sim: Simulation, seed_urdf: str) -> None:
    entity, plugins = spawn_seed(obstacle_sim, _small_camera(seed_urdf))
    plugin, config = plugins.cameras[0]
    assert plugin.name == "camera_controller"
    assert (config.image_topic, config.info_topic) == ("/camera1/image_raw", "/camera1/camera_info")
    image = Camera(obstacle_sim, entity, config).render()
    assert len(image) == 64 * 48 * 3
    # The red box straight ahead fills the image centre.
    centre = (24 * 64 + 32) * 3
    r, g, b = image[centre : centre + 3]
    assert r > 100 and r > 2 * g and r > 2 * b


@pytest.mark.parametrize("encoding", ["rgb8", "bgr8", "mono8"])
def test_camera_encodings_keep_each_pixels_channels(
    obstacle_sim: Simulation, seed_urdf: str, encoding: str
) -> None:
    """The rendered RGBA pixels, packed per encoding: the centre pixel (the red box) keeps its
    channels in the encoding's order, and every pixel is the one PyBullet rendered there."""
    entity, plugins = spawn_seed(obstacle_sim, _small_camera(seed_urdf))
    config = plugins.cameras[0][1]
    rgb = Camera(obstacle_sim, entity, config).render()
    image = Camera(obstacle_sim, entity, dataclasses.replace(config, encoding=encoding)).render()
    pixels = [rgb[i : i + 3] for i in range(0, len(rgb), 3)]
    if encoding == "rgb8":
        assert image == rgb
    elif encoding == "bgr8":
        assert image == b"".join(p[::-1] for p in pixels)
    else:
        assert image == bytes(sum(p) // 3 for p in pixels)
    centre = 24 * 64 + 32
    r, g, b = pixels[centre]
    assert r > 100 and r > 2 * g and r > 2 * b


def test_a_mirror_renders_what_the_world_shows(obstacle_sim: Simulation, seed_urdf: str) -> None:
    """The camera process's view: a second world put in the first's state by ``set_state``."""
    urdf = _small_camera(seed_urdf)
    entity = obstacle_sim.spawn("robot", urdf, (0.3, 0.2, 0.151, 0, 0, 2.0))
    obstacle_sim.step(240)
    config = load_plugins(obstacle_sim, entity, lambda _m: None).cameras[0][1]
    mirror = Simulation(load_world(resolve_world("obstacles")))
    try:
        twin = mirror.spawn("robot", urdf)  # at the origin, facing the red box
        twin_camera = Camera(mirror, twin, config)
        assert _red_fraction(twin_camera.render()) > 0.01
        base = obstacle_sim.base_state(entity)
        joints = {n: s[0] for n, s in obstacle_sim.joint_states(entity).items()}
        mirror.set_state(twin, base.position, base.orientation, joints)
        seen = Camera(obstacle_sim, entity, config).render()
        assert _red_fraction(seen) == 0.0
        assert twin_camera.render() == seen
    finally:
        mirror.close()


def test_camera_info_matches_gazebo(obstacle_sim: Simulation, seed_urdf: str) -> None:
    _, plugins = spawn_seed(obstacle_sim, seed_urdf)
    k, p = plugins.cameras[0][1].intrinsics()
    assert k[0] == pytest.approx(476.70, abs=0.01) and k[2] == 400.5
    assert p[3] == 0.0


def _trajectory_hash(urdf: str) -> str:
    sim = Simulation(load_world(resolve_world("empty")))
    try:
        entity, plugins = spawn_seed(sim, urdf)
        digest = hashlib.sha256()
        for v, w in ((0.5, 0.0), (0.2, 0.8), (0.0, -1.0)):
            drive(sim, entity, plugins, v, w, 0.5)
            base = sim.base_state(entity)
            digest.update(struct.pack("7d", *base.position, *base.orientation))
        return digest.hexdigest()
    finally:
        sim.close()


def test_stepping_is_deterministic(seed_urdf: str) -> None:
    assert _trajectory_hash(seed_urdf) == _trajectory_hash(seed_urdf)


def test_world_files_are_checked(tmp_path: Path) -> None:
    with pytest.raises(ModelError, match="not found"):
        resolve_world("no_such_world")
    bad = tmp_path / "bad.world"
    bad.write_text("<sdf><world><include><uri>model://house</uri></include></world></sdf>")
    with pytest.raises(ModelError, match="not supported"):
        load_world(bad)
    assert len(load_world(resolve_world("obstacles")).shapes) == 3
