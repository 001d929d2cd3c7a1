"""Simulate the three-wheeled robot, as seed 000's gazebo.launch.py does: robot_state_publisher
and joint_state_publisher with the URDF, Gazebo with the ROS init and factory plugins, and
spawn_entity.py after 8 s (Gazebo needs time to start before a model can be inserted).

Run:  launchkit run robot_wheel gazebo.launch.py
(`gazebo` runs launchkit's PyBullet server where Gazebo is not installed.)
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import ExecuteProcess, TimerAction
from launch_ros.actions import Node


def generate_launch_description():
    pkg_share = get_package_share_directory('robot_wheel')
    urdf_file = os.path.join(pkg_share, 'urdf', 'three_wheeled_robot.urdf')

    with open(urdf_file, 'r') as infp:
        robot_description = infp.read()

    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        name='robot_state_publisher',
        output='screen',
        parameters=[{'robot_description': robot_description, 'use_sim_time': True}],
    )

    joint_state_publisher = Node(
        package='joint_state_publisher',
        executable='joint_state_publisher',
        name='joint_state_publisher',
        output='screen',
        parameters=[{'use_sim_time': True}],
    )

    gazebo = ExecuteProcess(
        cmd=['gazebo', '--verbose', '-s', 'libgazebo_ros_init.so', '-s', 'libgazebo_ros_factory.so'],
        output='screen',
    )

    spawn_entity = TimerAction(
        period=8.0,
        actions=[
            Node(
                package='gazebo_ros',
                executable='spawn_entity.py',
                arguments=['-topic', 'robot_description', '-entity', 'threewheel_robot'],
                output='screen',
            )
        ],
    )

    return LaunchDescription([
        robot_state_publisher,
        joint_state_publisher,
        gazebo,
        spawn_entity,
    ])
