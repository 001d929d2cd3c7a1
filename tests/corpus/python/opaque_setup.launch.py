# Pattern: drivers such as ur_robot_driver and many bringups: an OpaqueFunction reading
# launch configurations with perform() and building the nodes from Python values.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def launch_setup(context, *args, **kwargs):
    robot_count = int(LaunchConfiguration('robot_count').perform(context))
    prefix = LaunchConfiguration('prefix').perform(context)
    use_sim_time = context.launch_configurations['use_sim_time'].lower() == 'true'
    nodes = []
    for index in range(robot_count):
        nodes.append(Node(
            package='demo_nodes_cpp', executable='talker',
            name=f'{prefix}talker_{index}', namespace=f'robot{index}',
            parameters=[{'use_sim_time': use_sim_time, 'index': index}],
        ))
    return nodes


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('robot_count', default_value='2'),
        DeclareLaunchArgument('prefix', default_value=''),
        DeclareLaunchArgument('use_sim_time', default_value='false'),
        OpaqueFunction(function=launch_setup),
    ])
