"""Python launch files written against ROS 2's launch API run through the same engine."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.frontend.python import launch_api
from launchkit.packages import PackageIndex, PythonPackage
from tests.conftest import EvaluateXml
from tests.engine.conftest import params_file
from tests.support import ament_package

GAZEBO_LIKE = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, LogInfo
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, PythonExpression


def _flag(name):
    value = LaunchConfiguration(name)
    return PythonExpression(['"--', name, '" if "true" == "', value, '" else ""'])


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('verbose', default_value='false', description='Set "true" for more'),
        DeclareLaunchArgument('world', default_value='empty.world'),
        ExecuteProcess(cmd=['server', LaunchConfiguration('world'), _flag('verbose')],
                       output='screen', name='server'),
        LogInfo(msg=['client on: ', LaunchConfiguration('world')],
                condition=IfCondition(LaunchConfiguration('verbose'))),
    ])
"""


def error_line(
    evaluate_xml: EvaluateXml, code: str, name: str, error: type[Exception], match: str
) -> int:
    """The line of the located ``error`` (its message matching ``match``) that evaluating
    ``code``, a file called ``name``, raises."""
    with pytest.raises(error, match=match) as caught:
        evaluate_xml(code, name=name)
    location = getattr(caught.value, "location", None)
    assert location is not None, caught.value
    return int(location.line)


def test_declarations_processes_and_conditions(evaluate_xml: EvaluateXml) -> None:
    quiet = evaluate_xml(GAZEBO_LIKE, name="gz.launch.py")
    # an empty word stays an empty argument, as in ROS
    assert quiet.process("server").cmd == ["server", "empty.world", ""]
    assert quiet.logs == []
    loud = evaluate_xml(GAZEBO_LIKE, {"verbose": "true", "world": "w"}, name="gz.launch.py")
    assert loud.process("server").cmd == ["server", "w", "--verbose"]
    assert loud.messages() == ["client on: w"]


def test_xml_includes_python_with_arguments(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "gz.launch.py").write_text(GAZEBO_LIKE)
    xml = """<launch>
      <include file="$(dirname)/gz.launch.py"><arg name="verbose" value="true"/></include>
    </launch>"""
    result = evaluate_xml(xml)
    assert result.process("server").cmd == ["server", "empty.world", "--verbose"]


def test_ros_node_and_package_lookup(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    share = tmp_path / "share"
    share.mkdir()
    packages = PackageIndex(
        ament_prefix_path="",
        python_packages={"demo": PythonPackage("demo", share, {"talker": "demo.talker"})},
    )
    code = """
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare
from launch.substitutions import PathJoinSubstitution


def generate_launch_description():
    return LaunchDescription([
        Node(package='demo', executable='talker', name='chat', namespace='ns',
             parameters=[{'rate': 5, 'frame': 'odom', 'enabled': True}],
             remappings=[('in', '/out')], arguments=['--x', 'a b'], output='screen'),
        Node(package='demo', executable='talker', exec_name='second',
             arguments=[PathJoinSubstitution([FindPackageShare('demo'), 'cfg.yaml'])]),
    ])
"""
    result = evaluate_xml(code, name="nodes.launch.py", packages=packages)
    first, second = result.processes
    assert first.cmd[:5] == [sys.executable, "-m", "demo.talker", "--x", "a b"]
    ros = first.cmd[first.cmd.index("--ros-args") + 1 :]
    assert ros[:4] == ["-r", "__node:=chat", "-r", "__ns:=/ns"]
    assert "in:=/out" in ros
    params = Path(ros[ros.index("--params-file") + 1]).read_text()
    assert "rate: 5" in params and "frame: odom" in params and "enabled: true" in params
    assert second.cmd[3] == f"{share}/cfg.yaml"


def test_unsupported_api_names_file_and_line(evaluate_xml: EvaluateXml) -> None:
    code = (
        "from launch import LaunchDescription\n"
        "from launch.actions import OpaqueCoroutine\n"
        "\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([OpaqueCoroutine(coroutine=print)])\n"
    )
    assert (
        error_line(
            evaluate_xml,
            code,
            "opaque.launch.py",
            LaunchFileError,
            "OpaqueCoroutine is not supported",
        )
        == 5
    )


def test_a_broken_python_file_is_a_located_error(evaluate_xml: EvaluateXml) -> None:
    code = "from launch import LaunchDescription\n\ndef generate_launch_description():\n    1/0\n"
    assert (
        error_line(evaluate_xml, code, "broken.launch.py", LaunchFileError, "ZeroDivisionError")
        == 4
    )


def test_unknown_import_is_a_clear_error(evaluate_xml: EvaluateXml) -> None:
    code = "import launch_testing_ros\n\ndef generate_launch_description():\n    pass\n"
    with pytest.raises(LaunchFileError, match="launch_testing_ros"):
        evaluate_xml(code, name="imports.launch.py")


def test_stand_in_modules_do_not_outlive_the_load(evaluate_xml: EvaluateXml) -> None:
    evaluate_xml(GAZEBO_LIKE, name="gz.launch.py")
    leaked = sys.modules.get("launch")
    assert getattr(leaked, "LaunchDescription", None) is not launch_api.LaunchDescription


def test_on_exit_shutdown(evaluate_xml: EvaluateXml) -> None:
    code = (
        "from launch import LaunchDescription\n"
        "from launch.actions import ExecuteProcess, Shutdown, LogInfo\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        "        ExecuteProcess(cmd=['true'], name='a', on_exit=Shutdown()),\n"
        "        ExecuteProcess(cmd=['true'], name='b', on_exit=[Shutdown()]),\n"
        "    ])\n"
    )
    result = evaluate_xml(code, name="exit.launch.py")
    assert result.process("a").on_exit_shutdown and result.process("b").on_exit_shutdown
    bad = code.replace("on_exit=[Shutdown()]", "on_exit=[LogInfo(msg='bye'), 'x']")
    assert (
        error_line(evaluate_xml, bad, "exit2.launch.py", LaunchFileError, "on_exit holds a str")
        == 6
    )


def test_command_concatenates_its_parts(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "model.txt").write_text("<robot/>")
    code = (
        "from launch import LaunchDescription\n"
        "from launch.actions import DeclareLaunchArgument, LogInfo\n"
        "from launch.substitutions import Command, LaunchConfiguration\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        f"        DeclareLaunchArgument('model', default_value='{tmp_path}/model.txt'),\n"
        "        LogInfo(msg=Command(['cat ', LaunchConfiguration('model')])),\n"
        "    ])\n"
    )
    assert evaluate_xml(code, name="cmd.launch.py").messages() == ["<robot/>"]


def test_ament_index_lookups(
    evaluate_xml: EvaluateXml, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    prefix = ament_package(tmp_path / "install", "amentpkg")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    code = (
        "from ament_index_python.packages import get_package_share_directory, get_package_prefix\n"
        "from launch import LaunchDescription\n"
        "from launch.actions import LogInfo\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        "        LogInfo(msg=get_package_share_directory('amentpkg')),\n"
        "        LogInfo(msg=get_package_prefix('amentpkg')),\n"
        "        LogInfo(msg=get_package_prefix('robot_wheel')),\n"
        "        LogInfo(msg=get_package_prefix('nopkg')),\n"
        "    ])\n"
    )
    assert error_line(evaluate_xml, code, "ament.launch.py", LaunchkitError, "nopkg") == 9
    found = evaluate_xml(
        code.replace("        LogInfo(msg=get_package_prefix('nopkg')),\n", ""),
        name="ament2.launch.py",
    )
    python_prefix = PackageIndex().find("robot_wheel").prefix  # a Python package's own prefix
    assert found.messages() == [str(prefix / "share" / "amentpkg"), str(prefix), str(python_prefix)]


def test_node_parameters_keep_their_order(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    share = tmp_path / "share"
    share.mkdir()
    params_file(tmp_path / "a.yaml", "rate: 5.0")
    params_file(tmp_path / "b.yaml", "rate: 9.0")
    packages = PackageIndex(
        ament_prefix_path="",
        python_packages={"demo": PythonPackage("demo", share, {"talker": "demo.talker"})},
    )
    code = f"""
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='demo', executable='talker', name='n',
             parameters=[{str(tmp_path / "a.yaml")!r}, {{'rate': 7.0, 'w': {{'r': 1}}}},
                         {str(tmp_path / "b.yaml")!r}, {{'late': True}}]),
    ])
"""
    (spec,) = evaluate_xml(code, name="order.launch.py", packages=packages).processes
    ros = spec.cmd[spec.cmd.index("--ros-args") + 1 :]
    files = [ros[i + 1] for i, arg in enumerate(ros) if arg == "--params-file"]
    # one params file per dict, between the files, as launch_ros passes them
    assert files[0] == str(tmp_path / "a.yaml") and files[2] == str(tmp_path / "b.yaml")
    assert Path(files[1]).read_text() == ("/**:\n  ros__parameters:\n    rate: 7.0\n    w.r: 1\n")
    assert Path(files[3]).read_text() == "/**:\n  ros__parameters:\n    late: true\n"
