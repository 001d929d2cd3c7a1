"""gazebo_ros's gzclient.launch.py: Gazebo's GUI client. launchkit has none: ``gzclient`` runs
its stand-in, which says where to see the simulation and waits until the launch stops."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument("verbose", default_value="false", description="print more"),
            ExecuteProcess(cmd=["gzclient"], output="screen"),
        ]
    )
