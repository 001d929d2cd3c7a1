"""Included by mixed_frontends.launch.yaml: logs its argument, then includes a YAML file."""

import os

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription, LogInfo
from launch.launch_description_sources import AnyLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    here = os.path.dirname(os.path.abspath(__file__))
    return LaunchDescription(
        [
            DeclareLaunchArgument("greeting"),
            LogInfo(msg=["python says: ", LaunchConfiguration("greeting")]),
            IncludeLaunchDescription(
                AnyLaunchDescriptionSource(os.path.join(here, "talker_listener.launch.yaml"))
            ),
        ]
    )
