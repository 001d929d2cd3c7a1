"""Seed 001's gazebo_and_rviz launch, in Python as The Construct's rosject writes it beside the
XML one: Gazebo (gazebo_ros's gazebo.launch.py) and the spawn of the URDF, robot_state_publisher
with the model run through xacro, and RViz with the package's configuration.

Run:  launchkit run robot_wheel gazebo_and_rviz.launch.py [start_gazebo:=false] [start_rviz:=false]
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import Command, LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    pkg_share = get_package_share_directory('robot_wheel')
    gazebo_ros_share = get_package_share_directory('gazebo_ros')
    default_model = os.path.join(pkg_share, 'urdf', 'three_wheeled_robot.urdf')
    rviz_config = os.path.join(pkg_share, 'config', 'robot.rviz')

    model = LaunchConfiguration('model')
    start_gazebo = LaunchConfiguration('start_gazebo')
    start_rviz = LaunchConfiguration('start_rviz')

    gazebo = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(gazebo_ros_share, 'launch', 'gazebo.launch.py')),
        condition=IfCondition(start_gazebo),
    )

    spawn_robot = Node(
        package='gazebo_ros',
        executable='spawn_entity.py',
        name='spawn_robot_urdf',
        arguments=['-file', model, '-x', '0.0', '-y', '0.0', '-z', '0.0', '-entity', 'my_robot'],
        output='screen',
        condition=IfCondition(start_gazebo),
    )

    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        name='robot_state_publisher',
        output='screen',
        parameters=[{
            'robot_description': ParameterValue(Command(['xacro ', model]), value_type=str),
            'use_sim_time': True,
        }],
    )

    rviz = Node(
        package='rviz2',
        executable='rviz2',
        name='rviz',
        arguments=['-d', rviz_config],
        parameters=[{'use_sim_time': True}],
        condition=IfCondition(start_rviz),
    )

    return LaunchDescription([
        DeclareLaunchArgument('model', default_value=default_model),
        DeclareLaunchArgument('start_gazebo', default_value='true'),
        DeclareLaunchArgument('start_rviz', default_value='true'),
        gazebo,
        spawn_robot,
        robot_state_publisher,
        rviz,
    ])
