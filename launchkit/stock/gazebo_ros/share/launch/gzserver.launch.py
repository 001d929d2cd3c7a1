"""gazebo_ros's gzserver.launch.py: the simulation server alone (here: the PyBullet server of
gazebo.launch.py, with the same arguments: world, verbose, pause, init, factory, gui,
real_time_factor, egl)."""

from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution, ThisLaunchFileDir


def generate_launch_description():
    server = PathJoinSubstitution([ThisLaunchFileDir(), "gazebo.launch.py"])
    return LaunchDescription([IncludeLaunchDescription(PythonLaunchDescriptionSource(server))])
