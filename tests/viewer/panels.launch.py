"""The panel tests' system: the viewer (rviz2 on ``viewer_port``) and the nodes of
``panel_nodes.py``, each its own process, two of them in the namespace ``/robot1``."""

import os
import sys

from launch.actions import DeclareLaunchArgument, ExecuteProcess
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription

NODES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "panel_nodes.py")
ROLES = {
    "talker": "/",
    "listener": "/",
    "driver": "/robot1",
    "follower": "/robot1",
    "logger": "/",
    "tuner": "/",
    "fibonacci": "/",
    "fib_client": "/",
}


def generate_launch_description() -> LaunchDescription:
    """rviz2 first (the router starts with the first node), then the panel nodes."""
    actions = [
        DeclareLaunchArgument("viewer_port", default_value="0"),
        Node(
            package="rviz2",
            executable="rviz2",
            name="rviz2",
            arguments=["--port", LaunchConfiguration("viewer_port")],
            output="screen",
        ),
    ]
    for role, namespace in ROLES.items():
        actions.append(
            ExecuteProcess(
                cmd=[sys.executable, NODES, role, "--ros-args", "-r", f"__ns:={namespace}"],
                name=role,
                output="screen",
            )
        )
    return LaunchDescription(actions)
