"""A spawned model's Gazebo plugins and sensors, turned into configured objects."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from launchkit.stock.gazebo_ros.sim.diff_drive import DiffDriveParams, wheel_geometry_warnings
from launchkit.stock.gazebo_ros.sim.engine import Entity, Simulation, SimulationError
from launchkit.stock.gazebo_ros.sim.joint_states import JOINT_STATE_PUBLISHER, JointStateOutput
from launchkit.stock.gazebo_ros.sim.model import ModelError, PluginSpec
from launchkit.stock.gazebo_ros.sim.sensors import CameraConfig, Lidar, LidarConfig

DIFF_DRIVE = "gazebo_ros_diff_drive"
RAY_SENSOR = "gazebo_ros_ray_sensor"
CAMERA = "gazebo_ros_camera"


@dataclass(frozen=True)
class PluginDefaults:
    """The server's choices where a model's blocks say nothing (see :func:`load_plugins`)."""

    #: The topic of a ray sensor whose ``<ros>`` block does not remap ``~/out``.
    ray_topic: str = "~/out"
    #: Sim Hz of the ``/joint_states`` of a model without a joint state plugin (0: none).
    joint_state_rate: float = 0.0


@dataclass
class EntityPlugins:
    """What runs for one entity: lidars and joint state streams, and diff drives and cameras
    (configured, run elsewhere)."""

    diff_drives: list[tuple[PluginSpec, DiffDriveParams]] = field(default_factory=list)
    joint_states: list[JointStateOutput] = field(default_factory=list)
    lidars: list[Lidar] = field(default_factory=list)
    cameras: list[tuple[PluginSpec, CameraConfig]] = field(default_factory=list)

    def poll_lidars(self, now: float) -> list[tuple[Lidar, list[float]]]:
        """Scans of the lidars due at sim time ``now``."""
        return [(lidar, lidar.scan()) for lidar in self.lidars if lidar.gate.due(now)]

    def state_rate(self, ceiling: float) -> float:
        """Hz of the state (joint states, ground truth) the diff drive and camera nodes read.

        The least common multiple of their update rates, so each keeps its exact period on the
        stream (30 Hz for the seed's 15 Hz drive and 30 Hz camera), at most ``ceiling``; the
        ceiling itself when a rate is not a whole number or is 0 (every step, in Gazebo).
        """
        rates = [params.update_rate for _, params in self.diff_drives]
        rates += [config.update_rate for _, config in self.cameras]
        if not rates or any(r <= 0 or r != int(r) for r in rates):
            return ceiling
        return float(min(math.lcm(*(int(r) for r in rates)), ceiling))


def load_plugins(
    sim: Simulation,
    entity: Entity,
    log: Callable[[str], object],
    defaults: PluginDefaults = PluginDefaults(),
) -> EntityPlugins:
    """Configure ``entity``'s plugins; :class:`SimulationError` on an unusable block."""
    found = EntityPlugins()
    spec = entity.spec
    for plugin in spec.plugins:
        if plugin.library == JOINT_STATE_PUBLISHER:
            try:
                found.joint_states.append(
                    JointStateOutput.from_plugin(plugin, entity.movable_joints)
                )
            except ModelError as exc:
                raise SimulationError(str(exc)) from None
            continue
        if plugin.library != DIFF_DRIVE:
            log(f"plugin '{plugin.name}' ({plugin.filename}) is not simulated; ignored")
            continue
        try:
            params = DiffDriveParams.from_tags(plugin.tags, _prefixed(log, plugin.name))
        except ValueError as exc:
            raise SimulationError(str(exc)) from None
        _check_diff_drive(sim, entity, plugin, params, log)
        found.diff_drives.append((plugin, params))
    driven = {j for _, p in found.diff_drives for j in (p.left_joint, p.right_joint)}
    if driven:
        for joint in sim.set_passive_friction(entity, driven):
            log(f"'{entity.name}': passive joint '{joint}' gets low friction (a caster)")
    for sensor in spec.sensors:
        libraries = {p.library for p in sensor.plugins}
        try:
            if sensor.type in ("ray", "gpu_ray") and RAY_SENSOR in libraries:
                config = LidarConfig.from_sensor(sensor, defaults.ray_topic)
                gazebo_topic = LidarConfig.from_sensor(sensor).topic
                if config.topic != gazebo_topic:
                    log(
                        f"ray sensor '{sensor.name}': publishing on {config.topic} (gazebo_ros "
                        f"would use {gazebo_topic}; remap ~/out in the plugin's <ros> block, or "
                        "set the server's ray_sensor_topic parameter, to choose)"
                    )
                if config.output_type != "sensor_msgs/LaserScan":
                    log(
                        f"ray sensor '{sensor.name}': {config.output_type} not supported; LaserScan"
                    )
                found.lidars.append(Lidar(sim, entity, config))
            elif sensor.type == "camera" and CAMERA in libraries:
                # The first plugin names the node, as CameraConfig reads it.
                found.cameras.append((sensor.plugins[0], CameraConfig.from_sensor(sensor, log)))
            else:
                log(f"sensor '{sensor.name}' (type {sensor.type}) has no ROS plugin; ignored")
        except ValueError as exc:
            raise SimulationError(str(exc)) from None
        if sensor.link not in entity.links:
            raise SimulationError(f"sensor '{sensor.name}' refers to unknown link '{sensor.link}'")
    if not found.joint_states and defaults.joint_state_rate > 0 and entity.movable_joints:
        found.joint_states.append(
            JointStateOutput.implicit_for(entity.movable_joints, defaults.joint_state_rate)
        )
    return found


def _prefixed(log: Callable[[str], object], name: str) -> Callable[[str], object]:
    return lambda message: log(f"diff drive '{name}': {message}")


def _check_diff_drive(
    sim: Simulation,
    entity: Entity,
    plugin: PluginSpec,
    params: DiffDriveParams,
    log: Callable[[str], object],
) -> None:
    for joint in (params.left_joint, params.right_joint):
        if joint not in entity.joints:
            raise SimulationError(
                f"diff drive '{plugin.name}': joint '{joint}' not in model '{entity.name}'"
            )
    if params.robot_base_frame not in entity.links:
        log(
            f"diff drive '{plugin.name}': robot_base_frame '{params.robot_base_frame}' is not a "
            f"link of '{entity.name}', so odom -> {params.robot_base_frame} is disconnected "
            "from the robot's tf tree"
        )
    children = {index: name for name, index in entity.links.items()}
    left_link = children[entity.joints[params.left_joint]]
    right_link = children[entity.joints[params.right_joint]]
    for warning in wheel_geometry_warnings(
        sim.position_in_root(entity, left_link)[1],
        sim.position_in_root(entity, right_link)[1],
        sim.joint_axis_in_root(entity, params.left_joint),
        sim.joint_axis_in_root(entity, params.right_joint),
    ):
        log(f"diff drive '{plugin.name}': {warning} (simulated as Gazebo does, not corrected)")
