"""Which ``sensor_msgs/JointState`` streams the simulator publishes for a spawned model.

gazebo_ros publishes joint states only from a ``libgazebo_ros_joint_state_publisher.so`` block:
its ``<joint_name>`` list, at its ``<update_rate>`` (100 Hz by default), on ``joint_states`` in
the plugin's namespace. The seed URDF has no such block, so under Gazebo nothing publishes
``/joint_states``: the seed has the user run ``joint_state_publisher`` (zeros) beside it, and the
wheels never turn in RViz. launchkit publishes a model without the block on ``/joint_states``
anyway (every movable joint, as PyBullet measures it), and stands back while another node
publishes that topic, so the seed's second-terminal ``joint_state_publisher`` does not fight it.
"""

from __future__ import annotations

from dataclasses import dataclass

from launchkit.stock.gazebo_ros.sim.model import ModelError, PluginSpec

JOINT_STATE_PUBLISHER = "gazebo_ros_joint_state_publisher"
#: gazebo_ros_joint_state_publisher's default ``<update_rate>``.
PLUGIN_DEFAULT_RATE = 100.0
DEFAULT_TOPIC = "/joint_states"


@dataclass(frozen=True)
class JointStateOutput:
    """One joint state stream: its topic, joints and rate (sim Hz).

    ``implicit`` marks the stream launchkit adds for a model without a joint state plugin; it
    pauses while another node publishes on its topic.
    """

    topic: str
    joints: tuple[str, ...]
    rate: float
    implicit: bool = False

    @classmethod
    def from_plugin(cls, plugin: PluginSpec, joints: list[str]) -> JointStateOutput:
        """Read a ``libgazebo_ros_joint_state_publisher.so`` block of a model with ``joints``."""
        names = tuple(n for n in plugin.repeated.get("joint_name", ()) if n)
        if not names:
            raise ModelError(
                f"joint state publisher '{plugin.name}': no <joint_name> (expected at least one)"
            )
        unknown = [n for n in names if n not in joints]
        if unknown:
            raise ModelError(
                f"joint state publisher '{plugin.name}': joint '{unknown[0]}' is not a movable "
                f"joint of the model (it has {', '.join(joints) or 'none'})"
            )
        rate_text = plugin.tags.get("update_rate", "")
        try:
            rate = float(rate_text) if rate_text else PLUGIN_DEFAULT_RATE
        except ValueError:
            raise ModelError(
                f"joint state publisher '{plugin.name}': <update_rate> is {rate_text!r} "
                "(expected a number)"
            ) from None
        topic = plugin.ros.remapped("joint_states")
        if not topic.startswith("/"):
            namespace = plugin.ros.namespace.strip("/")
            topic = f"/{namespace}/{topic}" if namespace else f"/{topic}"
        return cls(topic=topic, joints=names, rate=rate)

    @classmethod
    def implicit_for(cls, joints: list[str], rate: float) -> JointStateOutput:
        """The stream for a model without a joint state plugin: all its movable ``joints``."""
        return cls(topic=DEFAULT_TOPIC, joints=tuple(joints), rate=rate, implicit=True)
