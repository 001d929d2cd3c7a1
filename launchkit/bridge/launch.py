"""``launchkit run --bridge``: the bridge as one more supervised node of any launch."""

from __future__ import annotations

from launchkit.description.actions.executable import ProcessOptions
from launchkit.description.actions.node import ExecuteNode
from launchkit.description.launch_description import LaunchDescription
from launchkit.description.substitutions.base import Text

BRIDGE_ARGUMENT = "bridge"  # the robot launch's own switch
NODE_NAME = "ros2_bridge"


def add_bridge(description: LaunchDescription, arguments: dict[str, str]) -> None:
    """Run the bridge with the launch: through the file's own ``bridge`` argument when it
    declares one (so that it never runs twice), else as a node appended to the file."""
    if any(a.name == BRIDGE_ARGUMENT for a in description.declared_arguments()):
        arguments[BRIDGE_ARGUMENT] = "true"
        return
    name = (Text(NODE_NAME),)
    description.actions.append(
        ExecuteNode(
            (Text("launchkit_bridge"),),
            (Text("bridge"),),
            ProcessOptions(name=name, output=(Text("screen"),)),
            node_name=name,
        )
    )
