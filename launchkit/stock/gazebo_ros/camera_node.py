"""``camera``: a ``gazebo_ros_camera`` plugin as its own node process, rendering off the physics.

Gazebo renders sensors outside its physics thread, and a camera that cannot keep up publishes at a
lower rate while physics keeps real time. launchkit does the same with one process per camera
plugin, named after the plugin: it loads the server's world and the entity's model into a PyBullet
of its own (DIRECT; the EGL renderer plugin when ``egl`` is true; built when the image is first
subscribed, so an unwatched camera holds no renderer), mirrors the entity from the
server's ground truth and joint states (``/gazebo/{entity}/ground_truth`` and ``.../joint_states``,
paired by stamp) and publishes ``Image`` and ``CameraInfo`` stamped with that state's sim time.

It subscribes to the state, and renders, only while its image topic has subscribers; it renders
the newest state it has (older ones are dropped, never queued), at most at the sensor's
``update_rate`` in sim time. The server starts one per camera plugin (:mod:`plugin_processes`);
it also runs alone: ``launchkit exec gazebo_ros camera --ros-args -p entity:=NAME -p model:=URDF``.
Parameters: ``entity``, ``model`` (URDF text), ``sensor`` (default: the model's first camera),
``world`` (name or file, as the server's), ``egl`` (true: the EGL renderer plugin; TinyRenderer
if it cannot load).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.stock import _entry
from launchkit.stock.gazebo_ros import messages
from launchkit.stock.gazebo_ros.sim.engine import Simulation, SimulationError
from launchkit.stock.gazebo_ros.sim.model import ModelError, SensorSpec, parse_model
from launchkit.stock.gazebo_ros.sim.quiet import silence_c_stdout
from launchkit.stock.gazebo_ros.sim.sensors import Camera, CameraConfig, RateGate
from launchkit.stock.gazebo_ros.sim.world import load_world, resolve_world
from launchkit.stock.gazebo_ros.state_pairs import StatePairs, nanoseconds, subscribe_halves

#: Wall seconds between looks at the image topic's subscriber count while nobody watches.
IDLE_POLL = 0.1


class CameraConfigError(UserError):
    """Parameters the camera node cannot work with (exit status 2)."""


@dataclass(frozen=True)
class CameraNodeParams:
    """What the server tells a camera node besides the entity's name (its ROS parameters)."""

    sensor: str
    model: str
    world: str
    egl: bool

    def as_parameters(self) -> dict[str, object]:
        """The ROS parameters, by name."""
        return asdict(self)


class CameraNode:
    """Mirrors one entity from the server's state and publishes its camera's frames."""

    def __init__(self, node: ros.Node) -> None:
        self.node = node
        node, self.logger = self.node, self.node.get_logger()
        entity = str(node.declare_parameter("entity", "").value)
        model = str(node.declare_parameter("model", "").value)
        sensor = str(node.declare_parameter("sensor", "").value)
        world = str(node.declare_parameter("world", "empty").value) or "empty"
        egl = bool(node.declare_parameter("egl", True).value)
        if not entity or not model:
            raise CameraConfigError("parameters 'entity' and 'model' (URDF text) are required")
        try:
            self.world = load_world(resolve_world(world))
            self.config = _camera_config(parse_model(model).sensors, sensor)
        except (ModelError, ValueError) as exc:
            raise CameraConfigError(str(exc)) from None
        self.entity_name, self.model, self.egl = entity, model, egl
        # Built when the image is first subscribed: an unwatched camera costs no renderer
        # (the EGL plugin alone holds about 250 MB).
        self.camera: Camera | None = None
        c = self.config
        qos = ros.QoSProfile(depth=5, reliability=ros.ReliabilityPolicy.RELIABLE)
        self.image_pub = node.create_publisher(
            messages.message_class("sensor_msgs", "Image"), c.image_topic, qos
        )
        self.info_pub = node.create_publisher(
            messages.message_class("sensor_msgs", "CameraInfo"), c.info_topic, qos
        )
        self.gate = RateGate(c.update_rate)
        self.pairs: StatePairs[Any] = StatePairs()
        self.newest: tuple[int, Any, Any] | None = None  # (stamp ns, joint states, ground truth)
        self.rendered = -1
        self.state_subs: list[Any] = []
        self.received = False
        self.logger.info(
            f"camera '{c.sensor}' of '{entity}': {c.width}x{c.height} {c.encoding} at "
            f"{c.update_rate:g} Hz on '{c.image_topic}', rendered while subscribed"
        )

    def _renderer(self) -> Camera:
        """The camera over a world of its own (built on first use) with the entity in it."""
        if self.camera is not None:
            return self.camera
        if self.egl:
            silence_c_stdout()  # the EGL plugin prints a line per frame from C
        sim = Simulation(self.world, egl=self.egl, log=self.logger.warn)
        sim.log = lambda _message: None  # the server has said it all about this model
        try:
            entity = sim.spawn(self.entity_name, self.model)
        except SimulationError as exc:
            sim.close()
            raise CameraConfigError(str(exc)) from None
        self.camera = Camera(sim, entity, self.config)
        self.logger.info(f"renderer ready: {'EGL' if sim.egl else 'TinyRenderer'}")
        return self.camera

    def _watch(self) -> bool:
        """Whether the image has subscribers; follows the server's state only while it does."""
        watched = bool(self.image_pub.get_subscription_count() > 0)
        if watched and not self.state_subs:
            self.state_subs = subscribe_halves(
                self.node, self.entity_name, self._truth, self._joints
            )
            self._renderer()
            self.logger.info("image subscribed: rendering")
        elif not watched and self.state_subs:
            for sub in self.state_subs:
                self.node.destroy_subscription(sub)
            self.state_subs = []
            self.pairs.clear()
            self.newest = None
            self.logger.info("no image subscribers: rendering stopped")
        return watched

    def _truth(self, msg: Any) -> None:
        self.received = True
        self._keep(self.pairs.add_truth(nanoseconds(msg), msg))

    def _joints(self, msg: Any) -> None:
        self.received = True
        self._keep(self.pairs.add_joints(nanoseconds(msg), msg))

    def _keep(self, pair: tuple[Any, Any] | None) -> None:
        if pair is None:
            return
        joints, truth = pair
        key = nanoseconds(joints)
        if self.newest is None or key > self.newest[0]:
            self.newest = (key, joints, truth)
        if self.node.context.lockstep is not None:
            # the launch's clock waits for this callback: the frame due at this state's
            # instant is rendered and sent before the time moves on
            self.render_if_due()

    def _drain(self) -> None:
        """Run the callbacks already queued, so that the newest state is known."""
        while ros.ok():
            self.received = False
            ros.spin_once(self.node, timeout_sec=0.0)
            if not self.received:
                return

    def render_if_due(self) -> bool:
        """Render and publish the newest state if it is new and the update rate allows."""
        if self.newest is None:
            return False
        key, joints, truth = self.newest
        now = key / 1e9
        if key <= self.rendered or not self.gate.due(now):
            return False
        pose = truth.pose.pose
        camera = self._renderer()
        camera.sim.set_state(
            camera.entity,
            (pose.position.x, pose.position.y, pose.position.z),
            (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w),
            dict(zip(joints.name, (float(v) for v in joints.position), strict=False)),
        )
        frame = camera.render()
        self.rendered = key
        if not ros.ok():
            return False
        self.image_pub.publish(messages.image(self.config, now, frame))
        self.info_pub.publish(messages.camera_info(self.config, now))
        return True

    def run(self) -> None:
        """Follow, render and publish until shutdown."""
        while ros.ok():
            if not self._watch():
                ros.spin_once(self.node, timeout_sec=IDLE_POLL)
                continue
            ros.spin_once(self.node, timeout_sec=0.05)
            self._drain()
            self.render_if_due()

    def close(self) -> None:
        """Drop the mirrored world."""
        if self.camera is not None:
            self.camera.sim.close()


def _camera_config(sensors: tuple[SensorSpec, ...], name: str) -> CameraConfig:
    cameras = [s for s in sensors if s.type == "camera" and (not name or s.name == name)]
    if not cameras:
        raise CameraConfigError(f"the model has no camera sensor{f' {name!r}' if name else ''}")
    return CameraConfig.from_sensor(cameras[0], lambda _message: None)


def main(argv: list[str]) -> int:
    """Run the camera node until stopped; ``argv`` is the whole command line."""
    with _entry.ros_node(argv, "gazebo_ros_camera") as node:
        camera = CameraNode(node)
        try:
            camera.run()
        finally:
            camera.close()
    return 0


if __name__ == "__main__":
    _entry.run(main, "camera")
