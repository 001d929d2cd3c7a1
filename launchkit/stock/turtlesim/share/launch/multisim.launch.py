"""Two turtlesims side by side, in the namespaces turtlesim1 and turtlesim2."""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            Node(namespace=namespace, package="turtlesim", executable="turtlesim_node", output="screen")
            for namespace in ("turtlesim1", "turtlesim2")
        ]
    )
