"""The ``joint_state_publisher_gui`` executable: joint_state_publisher with sliders in the viewer.

launchkit has no window toolkit: the sliders are in the browser viewer that the ``rviz2``
stand-in serves. The node subscribes to ``~/slider_positions`` (sensor_msgs/JointState); the
viewer shows one slider per moving joint while this node runs and publishes their positions
there, and the node publishes them on ``/joint_states`` with the rest of its joints, as the Tk
window of ROS's node would. Without a viewer it publishes what joint_state_publisher does.
"""

from __future__ import annotations

import sys

import launchkit.ros as ros
from launchkit.ros.msgs.sensor_msgs.msg import JointState
from launchkit.stock import _entry
from launchkit.stock.joint_state_publisher.node import JointStatePublisher

#: Where the viewer's sliders publish (relative to the node: /joint_state_publisher_gui/...).
SLIDER_TOPIC = "~/slider_positions"


def with_sliders(node: ros.Node) -> None:
    """joint_state_publisher on ``node``, taking the viewer's slider positions too."""
    publisher = JointStatePublisher(node)
    sliders = node.create_subscription(JointState, SLIDER_TOPIC, publisher.on_source, 10)
    node.get_logger().info(
        f"joint sliders: open the viewer (rviz2) page; positions arrive on {sliders.topic}"
    )


def main(argv: list[str]) -> int:
    """Run joint_state_publisher under this node's name, taking slider positions too."""
    return _entry.spin(
        argv,
        "joint_state_publisher_gui",
        with_sliders,
        automatically_declare_parameters_from_overrides=True,
    )


if __name__ == "__main__":
    sys.exit(_entry.run(main, "joint_state_publisher_gui"))
