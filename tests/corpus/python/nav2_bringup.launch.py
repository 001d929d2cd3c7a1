# Pattern: navigation2 nav2_bringup bringup_launch.py (arguments, a namespaced GroupAction,
# SetRemap, SetParameter, includes of the package's other launch files with arguments).
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PythonExpression
from launch_ros.actions import PushRosNamespace, SetParameter, SetRemap


def generate_launch_description():
    bringup_dir = get_package_share_directory('nav2_bringup')
    launch_dir = os.path.join(bringup_dir, 'launch')

    namespace = LaunchConfiguration('namespace')
    use_namespace = LaunchConfiguration('use_namespace')
    slam = LaunchConfiguration('slam')
    map_yaml_file = LaunchConfiguration('map')
    use_sim_time = LaunchConfiguration('use_sim_time')
    params_file = LaunchConfiguration('params_file')
    autostart = LaunchConfiguration('autostart')

    declares = [
        DeclareLaunchArgument('namespace', default_value='', description='Top-level namespace'),
        DeclareLaunchArgument('use_namespace', default_value='false',
                              description='Whether to apply a namespace to the navigation stack'),
        DeclareLaunchArgument('slam', default_value='False', description='Whether run a SLAM'),
        DeclareLaunchArgument('map', default_value=os.path.join(bringup_dir, 'maps', 'map.yaml'),
                              description='Full path to map yaml file to load'),
        DeclareLaunchArgument('use_sim_time', default_value='false',
                              description='Use simulation (Gazebo) clock if true'),
        DeclareLaunchArgument('params_file',
                              default_value=os.path.join(bringup_dir, 'params', 'nav2_params.yaml'),
                              description='Full path to the ROS2 parameters file'),
        DeclareLaunchArgument('autostart', default_value='true',
                              description='Automatically startup the nav2 stack'),
    ]

    bringup_cmd_group = GroupAction([
        PushRosNamespace(condition=IfCondition(use_namespace), namespace=namespace),
        SetRemap(src='/tf', dst='tf'),
        SetRemap(src='/tf_static', dst='tf_static'),
        SetParameter('use_sim_time', use_sim_time),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(os.path.join(launch_dir, 'nav2_localization.launch.py')),
            condition=IfCondition(PythonExpression(['not ', slam])),
            launch_arguments={'namespace': namespace,
                              'map': map_yaml_file,
                              'params_file': params_file,
                              'autostart': autostart}.items()),
    ])

    return LaunchDescription(declares + [bringup_cmd_group])
