"""The simulation core: one PyBullet world in DIRECT mode, stepped deterministically.

No ROS here. The owner (the ``gzserver`` node, a test, a benchmark) spawns models from URDF text,
steps, reads joint and base states, and sets joint velocity targets. Sim time is the step count
times the step size, so a run driven by step count is bit-for-bit repeatable.
One thread must own a :class:`Simulation`.
"""

from __future__ import annotations

import os
import pkgutil
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from launchkit.rotations import conjugate, rotate
from launchkit.stock.gazebo_ros.sim.diff_drive import BaseState
from launchkit.stock.gazebo_ros.sim.materials import material_rgba
from launchkit.stock.gazebo_ros.sim.model import ModelError, ModelSpec, parse_model
from launchkit.stock.gazebo_ros.sim.scenery import build_scenery
from launchkit.stock.gazebo_ros.sim.world import WorldSpec

Pose = tuple[float, float, float, float, float, float]

#: Lateral friction of passive (undriven, non-fixed) links such as casters: the seed's caster
#: cannot roll (its joint spins about z only), so with default friction it drags
#: (docs/simulation.md, "The server").
PASSIVE_FRICTION = 0.0


class SimulationError(RuntimeError):
    """A request the world cannot honour (a duplicate or unknown entity, an unloadable model)."""


@dataclass
class Entity:
    """A spawned model: its body id, its spec and name -> index maps of links and joints."""

    name: str
    body: int
    spec: ModelSpec
    links: dict[str, int]
    joints: dict[str, int]
    movable_joints: list[str] = field(default_factory=list)

    def link_index(self, link: str) -> int:
        """PyBullet link index of ``link`` (-1 for the root)."""
        try:
            return self.links[link]
        except KeyError:
            raise SimulationError(f"model '{self.name}' has no link '{link}'") from None


def _import_pybullet() -> Any:
    import pybullet

    return pybullet


class Simulation:
    """A PyBullet world: ground and obstacles from a :class:`WorldSpec`, then spawned models."""

    def __init__(
        self,
        world: WorldSpec | None = None,
        *,
        time_step: float = 1.0 / 240.0,
        gui: bool = False,
        egl: bool = False,
        log: Callable[[str], object] = lambda _m: None,
    ) -> None:
        self.p = _import_pybullet()
        self.time_step = time_step
        self.steps = 0
        self.log = log
        mode = self.p.GUI if gui else self.p.DIRECT
        self.client: int = self.p.connect(mode)
        self.egl = False
        if egl:
            self.egl = self._load_egl()
        self.p.setGravity(0, 0, -9.81, physicsClientId=self.client)
        self.p.setTimeStep(time_step, physicsClientId=self.client)
        self.entities: dict[str, Entity] = {}
        self.world = world or WorldSpec("empty", True, ())
        self.ground = build_scenery(self.p, self.client, self.world)

    # -- world -------------------------------------------------------------------------------

    def _load_egl(self) -> bool:
        # Must happen before any body exists: the plugin never shows bodies made before it.
        loader = pkgutil.get_loader("eglRenderer")
        if loader is None:
            self.log("EGL renderer plugin not found; rendering with TinyRenderer")
            return False
        plugin = self.p.loadPlugin(
            loader.get_filename(),  # type: ignore[attr-defined]
            "_eglRendererPlugin",
            physicsClientId=self.client,
        )
        if plugin < 0:
            self.log("EGL renderer plugin failed to load; rendering with TinyRenderer")
            return False
        return True

    # -- time ----------------------------------------------------------------------------------

    @property
    def time(self) -> float:
        """Sim time in seconds (exactly steps × step size)."""
        return self.steps * self.time_step

    def step(self, count: int = 1) -> None:
        """Advance the physics ``count`` steps."""
        for _ in range(count):
            self.p.stepSimulation(physicsClientId=self.client)
            self.steps += 1

    # -- models --------------------------------------------------------------------------------

    def spawn(self, name: str, urdf_text: str, pose: Pose = (0, 0, 0, 0, 0, 0)) -> Entity:
        """Load a URDF (as text) named ``name`` at ``pose`` (x y z roll pitch yaw)."""
        if not name:
            raise SimulationError("an entity needs a name")
        if name in self.entities:
            raise SimulationError(f"entity '{name}' already exists")
        try:
            spec = parse_model(urdf_text)
        except ModelError as exc:
            raise SimulationError(str(exc)) from None
        body = self._load_urdf(urdf_text, pose)
        entity = self._index(name, body, spec)
        self._prepare(entity)
        self.entities[name] = entity
        return entity

    def _load_urdf(self, urdf_text: str, pose: Pose) -> int:
        fd, path = tempfile.mkstemp(suffix=".urdf", prefix="launchkit-")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(urdf_text)
            x, y, z, roll, pitch, yaw = pose
            try:
                body: int = self.p.loadURDF(
                    path,
                    basePosition=(x, y, z),
                    baseOrientation=self.p.getQuaternionFromEuler((roll, pitch, yaw)),
                    flags=self.p.URDF_USE_INERTIA_FROM_FILE,
                    physicsClientId=self.client,
                )
            except self.p.error as exc:
                raise SimulationError(f"PyBullet could not load the model: {exc}") from None
            return body
        finally:
            Path(path).unlink(missing_ok=True)

    def _index(self, name: str, body: int, spec: ModelSpec) -> Entity:
        p = self.p
        links = {spec.root_link: -1}
        joints: dict[str, int] = {}
        movable: list[str] = []
        for index in range(p.getNumJoints(body, physicsClientId=self.client)):
            info = p.getJointInfo(body, index, physicsClientId=self.client)
            joint_name = info[1].decode()
            links[info[12].decode()] = index
            joints[joint_name] = index
            if info[2] != p.JOINT_FIXED:
                movable.append(joint_name)
        return Entity(name, body, spec, links, joints, movable)

    def _prepare(self, entity: Entity) -> None:
        """Gazebo's defaults PyBullet lacks: free joints, friction, colours, on the ground."""
        p = self.p
        for joint in entity.movable_joints:
            # PyBullet gives every joint a velocity motor; Gazebo joints are free.
            p.setJointMotorControl2(
                entity.body,
                entity.joints[joint],
                p.VELOCITY_CONTROL,
                force=0,
                physicsClientId=self.client,
            )
        for link, mu in entity.spec.friction.items():
            if link in entity.links:
                p.changeDynamics(
                    entity.body,
                    entity.links[link],
                    lateralFriction=mu,
                    physicsClientId=self.client,
                )
        for link, material in entity.spec.materials.items():
            rgba = material_rgba(material)
            if link not in entity.links:
                self.log(f"<gazebo reference='{link}'>: no such link in '{entity.name}'")
            elif rgba is None:
                self.log(f"material '{material}' of link '{link}' is unknown; colour kept")
            else:
                p.changeVisualShape(
                    entity.body,
                    entity.links[link],
                    rgbaColor=rgba,
                    physicsClientId=self.client,
                )
        self._lift_onto_ground(entity)

    def set_passive_friction(self, entity: Entity, driven: set[str]) -> list[str]:
        """Low friction for links on movable joints that nothing drives (casters); their names."""
        passive = [j for j in entity.movable_joints if j not in driven]
        for joint in passive:
            self.p.changeDynamics(
                entity.body,
                entity.joints[joint],
                lateralFriction=PASSIVE_FRICTION,
                physicsClientId=self.client,
            )
        return passive

    def _lift_onto_ground(self, entity: Entity) -> None:
        if not self.world.ground_plane:
            return
        lowest = min(
            self.p.getAABB(entity.body, index, physicsClientId=self.client)[0][2]
            for index in entity.links.values()
        )
        if lowest < -1e-3:
            position, orientation = self.p.getBasePositionAndOrientation(
                entity.body, physicsClientId=self.client
            )
            lifted = (position[0], position[1], position[2] - lowest)
            self.p.resetBasePositionAndOrientation(
                entity.body, lifted, orientation, physicsClientId=self.client
            )
            self.log(
                f"'{entity.name}' was spawned {-lowest:.3f} m into the ground; "
                f"lifted to z={lifted[2]:.3f}"
            )

    def delete(self, name: str) -> None:
        """Remove entity ``name``."""
        entity = self.entities.pop(name, None)
        if entity is None:
            raise SimulationError(f"entity '{name}' does not exist")
        self.p.removeBody(entity.body, physicsClientId=self.client)

    def entity(self, name: str) -> Entity:
        """Entity ``name`` or :class:`SimulationError`."""
        try:
            return self.entities[name]
        except KeyError:
            raise SimulationError(f"entity '{name}' does not exist") from None

    # -- state ---------------------------------------------------------------------------------

    def joint_states(self, entity: Entity) -> dict[str, tuple[float, float, float]]:
        """``joint -> (position, velocity, applied effort)`` for every movable joint."""
        indices = [entity.joints[j] for j in entity.movable_joints]
        states = self.p.getJointStates(entity.body, indices, physicsClientId=self.client)
        return {
            name: (float(s[0]), float(s[1]), float(s[3]))
            for name, s in zip(entity.movable_joints, states, strict=False)
        }

    def base_state(self, entity: Entity) -> BaseState:
        """The root link's world pose and velocity."""
        position, orientation = self.p.getBasePositionAndOrientation(
            entity.body, physicsClientId=self.client
        )
        linear, angular = self.p.getBaseVelocity(entity.body, physicsClientId=self.client)
        return BaseState(tuple(position), tuple(orientation), tuple(linear), tuple(angular))

    def link_pose(
        self, entity: Entity, link: str
    ) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
        """World position and (x, y, z, w) orientation of ``link``'s frame."""
        index = entity.link_index(link)
        if index == -1:
            position, orientation = self.p.getBasePositionAndOrientation(
                entity.body, physicsClientId=self.client
            )
            return tuple(position), tuple(orientation)
        state = self.p.getLinkState(
            entity.body, index, computeForwardKinematics=True, physicsClientId=self.client
        )
        return tuple(state[4]), tuple(state[5])

    def joint_axis_in_root(self, entity: Entity, joint: str) -> tuple[float, float, float]:
        """A joint's axis expressed in the root link's frame (at the current pose)."""
        index = entity.joints[joint]
        axis = self.p.getJointInfo(entity.body, index, physicsClientId=self.client)[13]
        _, child_orientation = self.link_pose(entity, _child_link(entity, index))
        _, root_orientation = self.link_pose(entity, entity.spec.root_link)
        world = rotate(child_orientation, axis)
        return rotate(conjugate(root_orientation), world)

    def position_in_root(self, entity: Entity, link: str) -> tuple[float, float, float]:
        """A link frame's origin expressed in the root link's frame."""
        position, _ = self.link_pose(entity, link)
        root_position, root_orientation = self.link_pose(entity, entity.spec.root_link)
        offset = tuple(a - b for a, b in zip(position, root_position, strict=False))
        return rotate(conjugate(root_orientation), offset)

    def set_state(
        self,
        entity: Entity,
        position: tuple[float, float, float],
        orientation: tuple[float, float, float, float],
        joint_positions: dict[str, float],
    ) -> None:
        """Put ``entity`` in a pose without physics: base pose as :meth:`base_state` reports it
        and the named joints' positions (a renderer mirroring another world uses this)."""
        self.p.resetBasePositionAndOrientation(
            entity.body, position, orientation, physicsClientId=self.client
        )
        for joint, angle in joint_positions.items():
            index = entity.joints.get(joint)
            if index is not None:
                self.p.resetJointState(entity.body, index, angle, physicsClientId=self.client)

    def set_joint_velocities(
        self, entity: Entity, velocities: dict[str, float], max_force: float
    ) -> None:
        """Velocity-control targets (rad/s) with a force limit, as Gazebo's ``SetParam("vel")``."""
        for joint, velocity in velocities.items():
            if joint not in entity.joints:
                raise SimulationError(f"model '{entity.name}' has no joint '{joint}'")
            self.p.setJointMotorControl2(
                entity.body,
                entity.joints[joint],
                self.p.VELOCITY_CONTROL,
                targetVelocity=velocity,
                force=max_force,
                physicsClientId=self.client,
            )

    def close(self) -> None:
        """Disconnect from PyBullet (the world is gone)."""
        if self.client >= 0:
            self.p.disconnect(physicsClientId=self.client)
            self.client = -1


def _child_link(entity: Entity, joint_index: int) -> str:
    for name, index in entity.links.items():
        if index == joint_index:
            return name
    raise SimulationError(f"joint index {joint_index} has no child link")
