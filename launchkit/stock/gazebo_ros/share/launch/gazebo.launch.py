"""Start the simulator server as gazebo_ros's gazebo.launch.py does (PyBullet in place of Gazebo).

Arguments (gazebo_ros's names): world, verbose, pause, init, factory, gui, plus
real_time_factor and egl (cameras render with PyBullet's EGL plugin; false: TinyRenderer). One
difference: ``gui`` defaults to false here (the server is headless unless a GUI is asked for and
a display exists), and the GUI is drawn by the server itself, not gzclient.
"""

import sys

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess
from launch.substitutions import LaunchConfiguration, PythonExpression


def _plugin_if(argument, library):
    # '-s none' loads nothing, so each server plugin can be switched off by its argument.
    return PythonExpression(
        ["'", library, "' if '", LaunchConfiguration(argument), "'.lower() == 'true' else 'none'"]
    )


def generate_launch_description():
    arguments = [
        DeclareLaunchArgument(
            "world",
            default_value="",
            description="world file or shipped world name (empty, obstacles)",
        ),
        DeclareLaunchArgument("verbose", default_value="false", description="print more"),
        DeclareLaunchArgument("pause", default_value="false", description="start paused"),
        DeclareLaunchArgument(
            "init", default_value="true", description="load libgazebo_ros_init.so (/clock)"
        ),
        DeclareLaunchArgument(
            "factory",
            default_value="true",
            description="load libgazebo_ros_factory.so (spawn/delete)",
        ),
        DeclareLaunchArgument(
            "gui", default_value="false", description="show the PyBullet GUI (needs a display)"
        ),
        DeclareLaunchArgument(
            "real_time_factor",
            default_value="1.0",
            description="sim seconds per wall second (0: as fast as possible)",
        ),
        DeclareLaunchArgument(
            "egl",
            default_value="true",
            description="render cameras with PyBullet's EGL plugin (false: TinyRenderer)",
        ),
    ]
    server = ExecuteProcess(
        name="gzserver",
        cmd=[
            sys.executable,
            "-m",
            "launchkit.stock.gazebo_ros.gzserver",
            "-s",
            _plugin_if("init", "libgazebo_ros_init.so"),
            "-s",
            _plugin_if("factory", "libgazebo_ros_factory.so"),
            LaunchConfiguration("world"),
            "--ros-args",
            "-r",
            "__node:=gazebo",
            "-p",
            ["gui:=", LaunchConfiguration("gui")],
            "-p",
            ["verbose:=", LaunchConfiguration("verbose")],
            "-p",
            ["pause:=", LaunchConfiguration("pause")],
            "-p",
            # a double parameter: "0" must reach the node as 0.0 (an integer is refused)
            [
                "real_time_factor:=",
                PythonExpression(["float(", LaunchConfiguration("real_time_factor"), ")"]),
            ],
            "-p",
            ["egl:=", LaunchConfiguration("egl")],
        ],
        output="screen",
    )
    return LaunchDescription([*arguments, server])
