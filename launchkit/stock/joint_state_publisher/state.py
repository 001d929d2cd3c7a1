"""The joint positions a ``joint_state_publisher`` sends, without transport.

Every moving joint of the model starts at its default: ``zeros[name]`` when given, else 0, or
the middle of its limits when 0 lies outside them (as ROS's joint_state_publisher does). Joint
states from ``source_list`` topics overwrite the joints they name; mimic joints follow their
leader.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from launchkit.stock.urdf import Joint, RobotModel


@dataclass(frozen=True)
class JointStates:
    """One JointState's worth of data: names with their positions, velocities and efforts."""

    name: list[str]
    position: list[float]
    velocity: list[float]
    effort: list[float]


def default_position(joint: Joint, zeros: Mapping[str, float]) -> float:
    """Where ``joint`` rests until a source says otherwise."""
    if joint.name in zeros:
        return float(zeros[joint.name])
    lower, upper = joint.lower, joint.upper
    if lower is not None and upper is not None and (lower > 0.0 or upper < 0.0):
        return (lower + upper) / 2.0
    return 0.0


class JointStateMerger:
    """Keeps the current state of every moving joint and merges source messages into it."""

    def __init__(self, model: RobotModel, zeros: Mapping[str, float] | None = None) -> None:
        zeros = zeros or {}
        unknown = sorted(set(zeros) - {j.name for j in model.moving_joints})
        if unknown:
            raise ValueError(f"zeros names joints the robot does not move: {', '.join(unknown)}")
        self.model = model
        self.position = {j.name: default_position(j, zeros) for j in model.free_joints}
        self.velocity = dict.fromkeys(self.position, 0.0)
        self.effort = dict.fromkeys(self.position, 0.0)

    def merge(
        self,
        names: Sequence[str],
        positions: Sequence[float],
        velocities: Sequence[float] = (),
        efforts: Sequence[float] = (),
    ) -> None:
        """Take the values of the joints this robot drives from one source message."""
        for index, name in enumerate(names):
            if name not in self.position:
                continue
            if index < len(positions):
                self.position[name] = float(positions[index])
            if index < len(velocities):
                self.velocity[name] = float(velocities[index])
            if index < len(efforts):
                self.effort[name] = float(efforts[index])

    def current(self) -> JointStates:
        """Every moving joint in URDF order, mimic joints computed from their leaders."""
        out = JointStates([], [], [], [])
        for joint in self.model.moving_joints:
            position = self.model.position_of(joint, self.position)
            if position is None:  # mimics a joint that is not a free moving joint
                continue
            leader = joint.mimic.joint if joint.mimic is not None else joint.name
            scale = joint.mimic.multiplier if joint.mimic is not None else 1.0
            out.name.append(joint.name)
            out.position.append(position)
            out.velocity.append(scale * self.velocity.get(leader, 0.0))
            out.effort.append(self.effort.get(leader, 0.0))
        return out
