"""The differential drive: kinematics, acceleration limit and odometry, with no ROS and no physics.

This is the one implementation of ``libgazebo_ros_diff_drive.so``'s logic (gazebo_ros for ROS 2):
the simulator's in-process tests and the ``diff_drive`` node process both drive it. It works in
joint space exactly as Gazebo does (rim speed ``v ∓ ω·sep/2`` divided by the wheel radius, no sign
fix-ups), so a robot whose wheel axes or names are swapped behaves as it would in Gazebo;
:func:`wheel_geometry_warnings` says so instead of correcting it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

from launchkit.rotations import quaternion_from_yaw, yaw_of

#: ``odometry_source`` values, as gazebo_ros numbers them.
ENCODER = 0
WORLD = 1

_POSE_COVARIANCE_ROWS = (0, 7, 14, 21, 28, 35)

#: ROS 1 tag -> ROS 2 parameter. gazebo_ros for ROS 2 ignores these; launchkit honours them
#: (the seed URDF uses them and means them) and says so.
ROS1_ALIASES: Mapping[str, str] = {
    "commandTopic": "command_topic",
    "odometryTopic": "odometry_topic",
    "odometryFrame": "odometry_frame",
    "robotBaseFrame": "robot_base_frame",
    "publishWheelTF": "publish_wheel_tf",
    "publishOdomTF": "publish_odom_tf",
    "publishTf": "publish_odom_tf",
    "publishOdom": "publish_odom",
    "wheelSeparation": "wheel_separation",
    "wheelDiameter": "wheel_diameter",
    "wheelAcceleration": "max_wheel_acceleration",
    "wheelTorque": "max_wheel_torque",
    "updateRate": "update_rate",
    "odometrySource": "odometry_source",
    "leftJoint": "left_joint",
    "rightJoint": "right_joint",
}

#: ROS 1 tags with no meaning here (logged, then ignored).
ROS1_IGNORED = frozenset({"publishWheelJointState", "legacyMode", "rosDebugLevel", "alwaysOn"})


class DiffDriveConfigError(ValueError):
    """A diff drive plugin block or parameter set is unusable (a missing joint, a bad number)."""


@dataclass(frozen=True)
class DiffDriveParams:
    """The plugin's parameters, with the ROS 2 names and defaults of gazebo_plugins'
    ``gazebo_ros_diff_drive.cpp``."""

    left_joint: str
    right_joint: str
    wheel_separation: float = 0.34
    wheel_diameter: float = 0.15
    max_wheel_torque: float = 5.0
    max_wheel_acceleration: float = 0.0
    update_rate: float = 100.0
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_footprint"
    odometry_source: int = WORLD
    publish_odom: bool = False
    publish_odom_tf: bool = False
    publish_wheel_tf: bool = False
    covariance_x: float = 1e-5
    covariance_y: float = 1e-5
    covariance_yaw: float = 1e-3
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"

    @property
    def wheel_radius(self) -> float:
        """Half the wheel diameter."""
        return self.wheel_diameter / 2.0

    @property
    def update_period(self) -> float:
        """Seconds between control updates; 0 means every step."""
        return 1.0 / self.update_rate if self.update_rate > 0 else 0.0

    def as_parameters(self) -> dict[str, str | float | int | bool]:
        """These parameters as a flat ROS parameter dict (what the node process declares)."""
        return {name: getattr(self, name) for name in self.__dataclass_fields__}

    @classmethod
    def from_tags(
        cls, tags: Mapping[str, str], log: Callable[[str], object] = lambda _m: None
    ) -> DiffDriveParams:
        """Build from a plugin block's ``tag -> text``; ROS 1 tags are honoured and logged."""
        values: dict[str, str] = {}
        for tag, text in tags.items():
            if tag in ROS1_ALIASES:
                continue
            if tag in cls.__dataclass_fields__ or tag in ("num_wheel_pairs",):
                values[tag] = text
            elif tag in ROS1_IGNORED:
                log(f"ignoring ROS 1 tag <{tag}> (it has no meaning in ROS 2)")
            elif tag not in ("ros",):
                log(f"ignoring unknown tag <{tag}>")
        for tag, text in tags.items():
            name = ROS1_ALIASES.get(tag)
            if name is None:
                continue
            if name in values:
                log(f"ROS 1 tag <{tag}> ignored: <{name}> is given too")
                continue
            values[name] = text
            log(
                f"ROS 1 tag <{tag}> honoured as <{name}>={text} "
                "(gazebo_ros for ROS 2 ignores it; the URDF's author meant it)"
            )
        pairs = values.pop("num_wheel_pairs", "1")
        if pairs.strip() != "1":
            log(f"num_wheel_pairs={pairs}: only the first pair is driven")
        return cls.from_parameters(values)

    @classmethod
    def from_parameters(cls, values: Mapping[str, object]) -> DiffDriveParams:
        """Build from ROS 2 parameter names (strings are converted to the field's type)."""
        for required in ("left_joint", "right_joint"):
            if not str(values.get(required, "")).strip():
                raise DiffDriveConfigError(f"diff drive: <{required}> is required (a joint name)")
        params = cls(
            left_joint=str(values["left_joint"]).strip(),
            right_joint=str(values["right_joint"]).strip(),
        )
        changes: dict[str, object] = {}
        for name, value in values.items():
            if name in ("left_joint", "right_joint") or name not in cls.__dataclass_fields__:
                continue
            changes[name] = _convert(name, value, getattr(params, name))
        return replace(params, **changes)  # type: ignore[arg-type]


def _convert(name: str, value: object, default: object) -> object:
    text = str(value).strip()
    try:
        if isinstance(default, bool):
            if isinstance(value, bool):
                return value
            if text.lower() in ("true", "1"):
                return True
            if text.lower() in ("false", "0"):
                return False
            raise ValueError(text)
        if isinstance(default, int):
            if name == "odometry_source" and text.lower() in ("world", "encoder"):
                return WORLD if text.lower() == "world" else ENCODER
            number = int(text)
            if number not in (ENCODER, WORLD):
                raise ValueError(text)
            return number
        if isinstance(default, float):
            return float(text)
    except ValueError:
        kind = type(default).__name__
        raise DiffDriveConfigError(
            f"diff drive: <{name}> is {text!r} (expected a {kind})"
        ) from None
    return text


@dataclass(frozen=True)
class BaseState:
    """The model's root link in the world: pose (xyz, quaternion xyzw) and world-frame velocity."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    linear_velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    angular_velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Odometry:
    """What the plugin publishes on ``odom`` (and, as a transform, on ``/tf``)."""

    stamp: float
    frame_id: str
    child_frame_id: str
    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    linear: tuple[float, float, float]
    angular: tuple[float, float, float]
    pose_covariance: tuple[float, ...]
    twist_covariance: tuple[float, ...]


@dataclass(frozen=True)
class WheelCommand:
    """Joint velocity targets (rad/s) for the wheel joints, and the motor force limit (N·m)."""

    velocities: dict[str, float]
    max_torque: float


@dataclass(frozen=True)
class DriveUpdate:
    """One control update: what to publish and what to send to the joints."""

    odometry: Odometry
    command: WheelCommand


@dataclass
class DiffDriveController:
    """gazebo_ros_diff_drive's per-step logic; call :meth:`update` once per physics step.

    ``update`` returns ``None`` until ``update_period`` of sim time has passed since the last
    update (the plugin's rate gate); then it returns the odometry and the joint velocity targets.
    The last command persists: there is no timeout, as in the plugin.
    """

    params: DiffDriveParams
    start_time: float = 0.0
    _target: tuple[float, float] = (0.0, 0.0)
    _last_update: float | None = None
    _last_encoder: float | None = None
    _instr: list[float] = field(default_factory=lambda: [0.0, 0.0])
    _encoder_pose: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    _encoder_twist: tuple[float, float] = (0.0, 0.0)

    def set_command(self, linear_x: float, angular_z: float) -> bool:
        """A ``cmd_vel``: forward speed (m/s) and yaw rate (rad/s). A NaN or infinite value is
        refused (False) and the previous command stays: one would poison the physics, and
        with it the odometry, for good."""
        if not is_finite_command(linear_x, angular_z):
            return False
        self._target = (float(linear_x), float(angular_z))
        return True

    def reset(self, now: float) -> None:
        """Forget the command and the odometry, as after a world reset."""
        self._target = (0.0, 0.0)
        self._last_update = None
        self.start_time = now
        self._last_encoder = None
        self._instr = [0.0, 0.0]
        self._encoder_pose = [0.0, 0.0, 0.0]
        self._encoder_twist = (0.0, 0.0)

    def desired_rim_speeds(self) -> tuple[float, float]:
        """(left, right) rim speeds in m/s for the current command."""
        v, w = self._target
        half = w * self.params.wheel_separation / 2.0
        return (v - half, v + half)

    def update(
        self, now: float, wheel_velocities: tuple[float, float], base: BaseState
    ) -> DriveUpdate | None:
        """One physics step at sim time ``now`` with the (left, right) joint velocities (rad/s)."""
        if self.params.odometry_source == ENCODER:
            self._integrate_encoder(now, wheel_velocities)
        last = self.start_time if self._last_update is None else self._last_update
        dt = now - last
        # The slack keeps a step grid from slipping a beat on rounding (1/15 s on a 1/120 s grid).
        if self._last_update is not None and dt < self.params.update_period - 1e-9:
            return None
        odometry = self._odometry(now, base)
        command = self._wheel_command(dt, wheel_velocities)
        self._last_update = now
        return DriveUpdate(odometry, command)

    # -- control ---------------------------------------------------------------------------

    def _wheel_command(self, dt: float, wheel_velocities: tuple[float, float]) -> WheelCommand:
        p = self.params
        radius = p.wheel_radius
        desired = self.desired_rim_speeds()
        current = (wheel_velocities[0] * radius, wheel_velocities[1] * radius)
        accel = p.max_wheel_acceleration
        settled = all(abs(d - c) < 0.01 for d, c in zip(desired, current, strict=False))
        if accel == 0.0 or settled:
            rim = desired
        else:
            # Gazebo adds the clamped error to its instruction (not to the current speed).
            for i in (0, 1):
                error = desired[i] - current[i]
                step = min(error, accel * dt) if error >= 0 else max(error, -accel * dt)
                self._instr[i] += step
            rim = (self._instr[0], self._instr[1])
        return WheelCommand(
            {p.left_joint: rim[0] / radius, p.right_joint: rim[1] / radius}, p.max_wheel_torque
        )

    # -- odometry --------------------------------------------------------------------------

    def _integrate_encoder(self, now: float, wheel_velocities: tuple[float, float]) -> None:
        if self._last_encoder is None:
            self._last_encoder = now
            return
        dt = now - self._last_encoder
        self._last_encoder = now
        if dt <= 0.0:
            return
        radius, sep = self.params.wheel_radius, self.params.wheel_separation
        sl = wheel_velocities[0] * radius * dt
        sr = wheel_velocities[1] * radius * dt
        ssum, sdiff = sl + sr, sr - sl
        theta = self._encoder_pose[2]
        dx = ssum / 2.0 * math.cos(theta + sdiff / (2.0 * sep))
        dy = ssum / 2.0 * math.sin(theta + sdiff / (2.0 * sep))
        dtheta = sdiff / sep
        self._encoder_pose[0] += dx
        self._encoder_pose[1] += dy
        self._encoder_pose[2] += dtheta
        # As in the ROS 2 plugin: the speed is a magnitude, never negative.
        self._encoder_twist = (math.hypot(dx, dy) / dt, dtheta / dt)

    def _odometry(self, now: float, base: BaseState) -> Odometry:
        p = self.params
        if p.odometry_source == WORLD:
            position = base.position
            orientation = base.orientation
            yaw = yaw_of(orientation)
            vx, vy, _vz = base.linear_velocity
            c, s = math.cos(yaw), math.sin(yaw)
            linear = (c * vx + s * vy, c * vy - s * vx, 0.0)
            angular = (0.0, 0.0, base.angular_velocity[2])
        else:
            x, y, theta = self._encoder_pose
            position = (x, y, 0.0)
            orientation = quaternion_from_yaw(theta)
            linear = (self._encoder_twist[0], 0.0, 0.0)
            angular = (0.0, 0.0, self._encoder_twist[1])
        diagonal = (p.covariance_x, p.covariance_y, 1e12, 1e12, 1e12, p.covariance_yaw)
        covariance = tuple(
            diagonal[_POSE_COVARIANCE_ROWS.index(i)] if i in _POSE_COVARIANCE_ROWS else 0.0
            for i in range(36)
        )
        return Odometry(
            stamp=now,
            frame_id=p.odometry_frame,
            child_frame_id=p.robot_base_frame,
            position=position,
            orientation=orientation,
            linear=linear,
            angular=angular,
            pose_covariance=covariance,
            twist_covariance=covariance,
        )


def is_finite_command(linear_x: float, angular_z: float) -> bool:
    """Whether a command is a pair of real numbers (no NaN, no infinity)."""
    return math.isfinite(linear_x) and math.isfinite(angular_z)


def wheel_geometry_warnings(
    left_position_y: float,
    right_position_y: float,
    left_axis: tuple[float, float, float],
    right_axis: tuple[float, float, float],
) -> list[str]:
    """Where the wheels' placement in the base frame contradicts their names or drive direction.

    Positions and axes are in the base frame. Gazebo drives in joint space and corrects nothing;
    neither does launchkit, but it says what the user will see.
    """
    warnings: list[str] = []
    if left_position_y < right_position_y:
        warnings.append(
            f"the left wheel joint is at y={left_position_y:+.3f}, right of the right wheel joint "
            f"(y={right_position_y:+.3f}); REP-103 puts left at +y"
        )
    # A positive joint rate rolls the wheel centre along axis × (0, 0, r): its x part is axis_y·r.
    for label, axis in (("left", left_axis), ("right", right_axis)):
        if axis[1] < -0.5:
            warnings.append(
                f"a positive {label} wheel joint velocity drives the base toward -x "
                f"(axis {tuple(round(a, 3) for a in axis)} in the base frame)"
            )
    return warnings
