"""Display the three-wheeled robot in RViz, as seed 000's display.launch.py does: the URDF to
robot_state_publisher, sliders for the joints (joint_state_publisher_gui), and RViz.

Run:  launchkit run robot_wheel display.launch.py
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    pkg_share = get_package_share_directory('robot_wheel')
    urdf_file = os.path.join(pkg_share, 'urdf', 'three_wheeled_robot.urdf')
    rviz_config_file = os.path.join(pkg_share, 'config', 'robot.rviz')

    with open(urdf_file, 'r') as infp:
        robot_description = infp.read()

    robot_state_publisher_node = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        name='robot_state_publisher',
        output='screen',
        parameters=[{'robot_description': robot_description}],
    )

    joint_state_publisher_gui_node = Node(
        package='joint_state_publisher_gui',
        executable='joint_state_publisher_gui',
        name='joint_state_publisher_gui',
    )

    rviz_node = Node(
        package='rviz2',
        executable='rviz2',
        name='rviz2',
        output='screen',
        arguments=['-d', rviz_config_file],
    )

    return LaunchDescription([
        robot_state_publisher_node,
        joint_state_publisher_gui_node,
        rviz_node,
    ])
