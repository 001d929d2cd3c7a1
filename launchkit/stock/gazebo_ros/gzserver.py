"""``gzserver`` / ``gazebo``: the simulator server node (PyBullet in place of Gazebo).

Accepts Gazebo's command line (``gazebo --verbose -s libgazebo_ros_init.so -s
libgazebo_ros_factory.so [WORLD]``) and ROS arguments after ``--ros-args``. With the init plugin it
publishes ``/clock``; with the factory plugin it serves ``/spawn_entity`` and ``/delete_entity``.
Spawned models get their lidars and joint states published, and their diff drives and cameras
run as node processes of their own, started by the launcher under ``launchkit run`` and by the
server otherwise (:mod:`plugin_processes`): the physics loop never renders. Parameters:
``real_time_factor`` (1.0; 0 = as fast as possible), ``publish_rate`` (/clock Hz, 10),
``time_step`` (s, 1/240), ``state_rate`` (the most Hz of the joint states and ground truth the
diff drive and cameras read, 120; see :meth:`EntityPlugins.state_rate`), ``gui`` (false), ``egl``
(the cameras render with PyBullet's EGL plugin, TinyRenderer if it cannot load; true),
``world``, and two choices where launchkit differs from gazebo_ros for the seed's sake:
``ray_sensor_topic`` (``scan``: where a ray sensor publishes unless its ``<ros>`` block remaps
``~/out``; ``~/out`` is gazebo_ros's choice) and ``joint_state_rate`` (50 Hz of ``/joint_states``
for a model without a joint state plugin; 0 for none, as in Gazebo; see
:mod:`sim.joint_states`).
"""

from __future__ import annotations

import faulthandler
import math
import os
import signal
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import launchkit.ros as ros
from launchkit.rotations import quaternion_to_rpy
from launchkit.stock import _entry
from launchkit.stock.gazebo_ros import messages
from launchkit.stock.gazebo_ros.camera_node import CameraNodeParams
from launchkit.stock.gazebo_ros.plugin_processes import PluginProcesses
from launchkit.stock.gazebo_ros.server_options import ServerOptions, UsageError, parse_server_args
from launchkit.stock.gazebo_ros.sim.diff_drive import Odometry
from launchkit.stock.gazebo_ros.sim.engine import Entity, Simulation, SimulationError
from launchkit.stock.gazebo_ros.sim.joint_states import JointStateOutput
from launchkit.stock.gazebo_ros.sim.model import ModelError
from launchkit.stock.gazebo_ros.sim.pacing import Pacer
from launchkit.stock.gazebo_ros.sim.plugins import EntityPlugins, PluginDefaults, load_plugins
from launchkit.stock.gazebo_ros.sim.sensors import RateGate
from launchkit.stock.gazebo_ros.sim.world import load_world, resolve_world

#: Seconds a stop request may take before the server prints its stacks and exits hard (under
#: ROS's default SIGINT -> SIGKILL escalation of 10 s).
STOP_WATCHDOG = 6.0


@dataclass
class _Spawned:
    """One spawned entity's publishers and plugins."""

    entity: Entity
    plugins: EntityPlugins
    state_pub: Any
    truth_pub: Any
    sensor_pubs: dict[str, Any] = field(default_factory=dict)
    joint_state_pubs: list[tuple[JointStateOutput, Any, RateGate]] = field(default_factory=list)


class SimServer:
    """The node: owns the :class:`Simulation` from one thread and paces it."""

    def __init__(self, node: ros.Node, options: ServerOptions) -> None:
        self.node = node
        self.logger = self.node.get_logger()
        p = self.node
        rtf = float(p.declare_parameter("real_time_factor", 1.0).value)
        publish_rate = float(p.declare_parameter("publish_rate", 10.0).value)
        time_step = float(p.declare_parameter("time_step", 1.0 / 240.0).value)
        state_rate = float(p.declare_parameter("state_rate", 120.0).value)
        gui = bool(p.declare_parameter("gui", options.gui).value)
        self.egl = bool(p.declare_parameter("egl", True).value)
        world_name = str(p.declare_parameter("world", options.world).value) or "empty"
        self.plugin_defaults = PluginDefaults(
            ray_topic=str(p.declare_parameter("ray_sensor_topic", "scan").value) or "~/out",
            joint_state_rate=float(p.declare_parameter("joint_state_rate", 50.0).value),
        )
        p.declare_parameter("verbose", options.verbose)
        if bool(p.declare_parameter("pause", options.paused).value):
            self.logger.warn("starting paused is not supported; the world runs")
        if gui and not os.environ.get("DISPLAY"):
            self.logger.warn("a GUI was asked for but there is no DISPLAY; running headless")
            gui = False
        self.world_file = str(resolve_world(world_name).resolve())
        world = load_world(Path(self.world_file))
        self.sim = Simulation(world, time_step=time_step, gui=gui, log=self.logger.info)
        self.logger.info(
            f"world '{world.name}' loaded ({len(world.shapes)} obstacles), step {time_step:.5f} s, "
            f"real-time factor {rtf if rtf > 0 else 'unlimited'}"
        )
        self.pacer = Pacer(rtf)
        self.clock_gate = RateGate(publish_rate)
        self.state_rate = state_rate
        self.state_gates: dict[str, RateGate] = {}
        self.spawned: dict[str, _Spawned] = {}
        #: Topics where the implicit joint state streams pause: another node publishes there.
        self.yielded_topics: set[str] = set()
        self.children = PluginProcesses(self.logger.info)
        self.sensor_qos = ros.QoSProfile(depth=5, reliability=ros.ReliabilityPolicy.RELIABLE)
        self.clock_pub = None
        #: In a lockstep launch the launch's clock drives the physics (see run_lockstep).
        self.lockstep = node.context.lockstep is not None
        if self.lockstep:
            self.logger.info(
                "lockstep: the physics follows the launch's /clock and holds it at every "
                "instant something is due"
            )
        elif options.ros_init:
            clock_qos = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
            self.clock_pub = p.create_publisher(
                messages.message_class("rosgraph_msgs", "Clock"), "/clock", clock_qos
            )
        if options.factory:
            spawn_type = messages.service_class("gazebo_msgs", "SpawnEntity")
            delete_type = messages.service_class("gazebo_msgs", "DeleteEntity")
            p.create_service(spawn_type, "/spawn_entity", self._spawn)
            p.create_service(delete_type, "/delete_entity", self._delete)
        self.running = True

    # -- services --------------------------------------------------------------------------

    def _spawn(self, request: Any, response: Any) -> Any:
        name = str(request.name)
        xml = str(request.xml)
        try:
            if xml.lstrip().startswith("<sdf") or "<sdf" in xml[:200]:
                raise SimulationError("SDF models are not supported (expected a URDF <robot>)")
            pose = request.initial_pose
            if str(request.reference_frame) not in ("", "world"):
                self.logger.warn(
                    f"reference_frame '{request.reference_frame}' ignored; the pose is in world"
                )
            o = pose.orientation
            roll, pitch, yaw = quaternion_to_rpy((o.x, o.y, o.z, o.w))
            if pose.orientation.w == 0 and pose.orientation.z == 0 and pose.orientation.x == 0:
                roll = pitch = yaw = 0.0  # an all-zero quaternion means "no rotation"
            entity = self.sim.spawn(
                name, xml, (pose.position.x, pose.position.y, pose.position.z, roll, pitch, yaw)
            )
            try:
                plugins = load_plugins(self.sim, entity, self.logger.info, self.plugin_defaults)
            except SimulationError:
                self.sim.delete(name)
                raise
        except (SimulationError, ModelError) as exc:
            self.logger.error(f"SpawnEntity: failed to spawn [{name}]: {exc}")
            response.success = False
            response.status_message = f"SpawnEntity: {exc}"
            return response
        self._start_entity(entity, plugins, xml)
        response.success = True
        response.status_message = f"SpawnEntity: Successfully spawned entity [{name}]"
        self.logger.info(response.status_message)
        return response

    def _delete(self, request: Any, response: Any) -> Any:
        name = str(request.name)
        try:
            self.sim.delete(name)
        except SimulationError as exc:
            response.success = False
            response.status_message = f"DeleteEntity: {exc}"
            return response
        self.children.stop_entity(name)
        self.spawned.pop(name, None)
        response.success = True
        response.status_message = f"DeleteEntity: Successfully deleted entity [{name}]"
        self.logger.info(response.status_message)
        return response

    def _start_entity(self, entity: Entity, plugins: EntityPlugins, model: str) -> None:
        p, name = self.node, entity.name
        joint_state = messages.message_class("sensor_msgs", "JointState")
        odometry = messages.message_class("nav_msgs", "Odometry")
        spawned = _Spawned(
            entity,
            plugins,
            p.create_publisher(joint_state, messages.STATE_TOPIC.format(entity=name), 10),
            p.create_publisher(odometry, messages.GROUND_TRUTH_TOPIC.format(entity=name), 10),
        )
        p.create_subscription(
            joint_state,
            messages.COMMAND_TOPIC.format(entity=name),
            lambda msg, n=name: self._command(n, msg),
            10,
        )
        for lidar in plugins.lidars:
            spawned.sensor_pubs[lidar.config.topic] = p.create_publisher(
                messages.message_class("sensor_msgs", "LaserScan"),
                lidar.config.topic,
                self.sensor_qos,
            )
        for output in plugins.joint_states:
            publisher = p.create_publisher(joint_state, output.topic, 10)
            spawned.joint_state_pubs.append((output, publisher, RateGate(output.rate)))
            if output.implicit:
                self.logger.info(
                    f"'{name}' has no joint state plugin: publishing its joints on {output.topic} "
                    f"at {output.rate:g} Hz while no other node does (joint_state_rate:=0 for none)"
                )
        self.spawned[name] = spawned
        self.state_gates[name] = RateGate(plugins.state_rate(self.state_rate))
        self._yield_joint_state_topics()  # joint_state_publisher may be running already
        for plugin, params in plugins.diff_drives:
            self.children.start_diff_drive(name, plugin, params)
        for plugin, config in plugins.cameras:
            camera = CameraNodeParams(config.sensor, model, self.world_file, self.egl)
            self.children.start_camera(name, plugin, camera)
        if self.lockstep:
            self._reschedule()  # its first state is due now

    def _command(self, entity: str, msg: Any) -> None:
        spawned = self.spawned.get(entity)
        if spawned is None:
            return
        names = list(msg.name)
        velocities = list(msg.velocity)
        efforts = list(msg.effort)
        force = max(efforts) if efforts else 5.0
        try:
            self.sim.set_joint_velocities(
                spawned.entity, dict(zip(names, velocities, strict=False)), force
            )
        except SimulationError as exc:
            self.logger.warn(f"joint command for '{entity}' ignored: {exc}")

    # -- loop ------------------------------------------------------------------------------

    def _publish(self, now: float) -> None:
        if self.clock_pub is not None and self.clock_gate.due(now):
            self.clock_pub.publish(messages.clock(now))
        for name, spawned in self.spawned.items():
            if self.state_gates[name].due(now):
                self._publish_state(now, spawned)
            for output, publisher, gate in spawned.joint_state_pubs:
                if output.implicit and output.topic in self.yielded_topics:
                    continue
                if gate.due(now):
                    publisher.publish(self._joint_state(now, spawned.entity, output.joints))
            for lidar, ranges in spawned.plugins.poll_lidars(now):
                scan = messages.laser_scan(lidar.config, now, ranges)
                spawned.sensor_pubs[lidar.config.topic].publish(scan)

    def _publish_state(self, now: float, spawned: _Spawned) -> None:
        # The diff drive and the camera nodes pair these two by stamp.
        base = self.sim.base_state(spawned.entity)
        spawned.truth_pub.publish(
            messages.odometry(_ground_truth(now, spawned.entity.spec.root_link, base))
        )
        spawned.state_pub.publish(self._joint_state(now, spawned.entity))

    def _joint_state(self, now: float, entity: Entity, joints: tuple[str, ...] = ()) -> Any:
        """A ``JointState`` of ``joints`` (all movable joints when empty) at ``now``."""
        states = self.sim.joint_states(entity)
        names = list(joints) or list(states)
        return messages.joint_state(
            now,
            names,
            [states[n][0] for n in names],
            [states[n][1] for n in names],
            [states[n][2] for n in names],
        )

    def _yield_joint_state_topics(self) -> None:
        """Pause the implicit joint state streams on topics another node publishes, and resume
        them when it is gone."""
        ours: dict[str, int] = {}
        implicit: set[str] = set()
        for spawned in self.spawned.values():
            for output, _, _ in spawned.joint_state_pubs:
                ours[output.topic] = ours.get(output.topic, 0) + 1
                if output.implicit:
                    implicit.add(output.topic)
        for topic in implicit:
            others = self.node.count_publishers(topic) - ours[topic]
            if others > 0 and topic not in self.yielded_topics:
                self.yielded_topics.add(topic)
                self.logger.info(
                    f"another node publishes {topic}; the simulator stops publishing there"
                )
            elif others <= 0 and topic in self.yielded_topics:
                self.yielded_topics.discard(topic)
                self.logger.info(f"no other node publishes {topic}; the simulator publishes it")

    def run(self) -> None:
        """Step, publish and pace until shutdown."""
        if self.lockstep:
            self.run_lockstep()
            return
        steps_between_spins = 8
        while self.running and ros.ok():
            # Ground truth and joint states go out before the step so that a subscriber sees a
            # consistent state at the stamp.
            self._publish(self.sim.time)
            self.sim.step()
            wait = self.pacer.wait_needed(self.sim.time)
            if wait > 0:
                ros.spin_once(self.node, timeout_sec=min(wait, 0.05))
            elif self.sim.steps % steps_between_spins == 0:
                ros.spin_once(self.node, timeout_sec=0.0)
            if self.sim.steps % 240 == 0:
                self.children.supervise()
                self._yield_joint_state_topics()

    def run_lockstep(self) -> None:
        """Step when the launch's clock moves, until shutdown.

        A timer on the node's (simulated) clock steps the physics up to the time it fires at,
        publishing what is due on the way, and sets itself to the next step at which something
        is due (a state, joint states, a scan): the launch's clock stops there, so every
        message of that instant is handled (the diff drive's command among them) before the
        physics goes on.
        """
        self._step_timer = self.node.create_timer(self.sim.time_step, self._catch_up)
        executor = ros.SingleThreadedExecutor(context=self.node.context)
        executor.add_node(self.node)
        try:
            while self.running and ros.ok():
                executor.spin_once(timeout_sec=0.1)
        finally:
            executor.remove_node(self.node)

    def _catch_up(self) -> None:
        now_ns = self.node.get_clock().now().nanoseconds
        while _ns(self._step_time(1)) <= now_ns:
            self.sim.step()
            self._publish(self.sim.time)
            if self.sim.steps % 240 == 0:
                self.children.supervise()
                self._yield_joint_state_topics()
        self._reschedule()

    def _reschedule(self) -> None:
        """Set the step timer to the next step at which something is due."""
        now_ns = self.node.get_clock().now().nanoseconds
        self._step_timer.timer_period_ns = max(1, self._next_event_ns() - now_ns)

    def _step_time(self, ahead: int) -> float:
        """The sim time ``ahead`` steps from now (as :attr:`Simulation.time` will say)."""
        return (self.sim.steps + ahead) * self.sim.time_step

    def _next_event_ns(self) -> int:
        """The first step ahead at which something is published (at most a second ahead)."""
        gates = [g for name, g in self.state_gates.items() if name in self.spawned]
        for spawned in self.spawned.values():
            gates += [lidar.gate for lidar in spawned.plugins.lidars]
            gates += [
                gate
                for output, _, gate in spawned.joint_state_pubs
                if not (output.implicit and output.topic in self.yielded_topics)
            ]
        steps_per_second = max(1, round(1.0 / self.sim.time_step))
        ahead = min([self._steps_until(gate) for gate in gates] + [steps_per_second])
        return _ns(self._step_time(ahead))

    def _steps_until(self, gate: RateGate) -> int:
        """How many steps ahead ``gate`` is first due (at least 1)."""
        due = gate.next_due()
        if due is None:
            return 1
        ahead = max(1, math.ceil(due / self.sim.time_step) - self.sim.steps)
        while ahead > 1 and gate.is_due(self._step_time(ahead - 1)):  # float rounding
            ahead -= 1
        while not gate.is_due(self._step_time(ahead)):
            ahead += 1
        return ahead

    def close(self) -> None:
        """Stop the children and the physics."""
        self.children.stop()
        self.sim.close()


def _ns(seconds: float) -> int:
    return round(seconds * 1e9)


def _ground_truth(now: float, root: str, base: Any) -> Any:
    zeros = tuple(0.0 for _ in range(36))
    return Odometry(
        stamp=now,
        frame_id="world",
        child_frame_id=root,
        position=base.position,
        orientation=base.orientation,
        linear=base.linear_velocity,
        angular=base.angular_velocity,
        pose_covariance=zeros,
        twist_covariance=zeros,
    )


def main(argv: list[str]) -> int:
    """Run the server until stopped; ``argv`` is the whole command line."""
    try:
        options = parse_server_args(argv[1:])
        resolve_world(options.world)
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    server: SimServer | None = None
    stop_requested = False

    def _stop(_signum: int, _frame: object) -> None:
        nonlocal stop_requested
        if not stop_requested:
            # If stopping itself gets stuck, print where and exit before the launcher's SIGKILL.
            faulthandler.dump_traceback_later(STOP_WATCHDOG, exit=True)
        stop_requested = True
        if server is not None:
            server.running = False

    # `kill -USR1 PID` prints every thread's stack: what a stuck server is doing.
    faulthandler.register(signal.SIGUSR1, all_threads=True)
    # Installed before the world load, so an early Ctrl-C still ends cleanly, and again after
    # it: initialising the ROS layer installs its handlers over these.
    signal.signal(signal.SIGTERM, _stop)
    signal.signal(signal.SIGINT, _stop)
    try:
        with _entry.ros_node(argv, "gazebo") as node:
            server = SimServer(node, options)
            signal.signal(signal.SIGTERM, _stop)
            signal.signal(signal.SIGINT, _stop)
            # a Ctrl-C while the world loaded went to the ROS layer's handler, not to _stop
            server.running = not stop_requested and node.context.ok()
            try:
                server.run()
            finally:
                server.close()
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    return 0


if __name__ == "__main__":
    _entry.run(main, "gazebo")
