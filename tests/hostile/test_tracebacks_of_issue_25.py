"""Inputs that printed a traceback (issue #25, point 5) and are now one located line, exit
status 2: YAML explicit tags in launch files and in every stock node's ``--params-file``,
misused Python launch API, a NUL byte in ``$(command)`` or a process's command line or
environment."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from tests.hostile.helpers import assert_located_error, launchkit

#: tag -> what the error says
TAGS = {
    "!!timestamp x": "'x' is not a valid !!timestamp",
    "!!bool maybe": "'maybe' is not a valid !!bool",
    '!!int ""': "'' is not a valid !!int",
    "!!float abc": "'abc' is not a valid !!float",
    "!!binary a": "'a' is not a valid !!binary",
    "!!python/name:os.system x": "YAML tag 'tag:yaml.org,2002:python/name:os.system' is not",
    "!!python/object/apply:os.system [id]": "YAML tag 'tag:yaml.org,2002:python/object/apply",
}

#: Every stock executable that takes parameters (python -m MODULE), with what it needs more.
STOCK_NODES = {
    "launchkit.stock.robot_state_publisher.node": [],
    "launchkit.stock.joint_state_publisher.node": [],
    "launchkit.stock.joint_state_publisher_gui.node": [],
    "launchkit.stock.gazebo_ros.gzserver": [],
    "launchkit.stock.gazebo_ros.diff_drive_node": [],
    "launchkit.stock.gazebo_ros.camera_node": [],
    "launchkit.stock.rclcpp_components.container": [],
    "launchkit.stock.rviz2.node": ["--port", "0"],
    "launchkit.bridge": [],
}


@pytest.mark.parametrize("tag", sorted(TAGS))
def test_explicit_yaml_tags_in_a_launch_file(tmp_path: Path, tag: str) -> None:
    path = tmp_path / "tags.launch.yaml"
    path.write_text(f"launch:\n- arg:\n    name: a\n    default: {tag}\n")
    assert_located_error(launchkit("check", path), r"tags\.launch\.yaml:4:\d+", TAGS[tag])


@pytest.mark.parametrize("tag", sorted(TAGS))
def test_explicit_yaml_tags_in_a_params_file(tmp_path: Path, tag: str) -> None:
    params = tmp_path / "params.yaml"
    params.write_text(f"/**:\n  ros__parameters:\n    p: {tag}\n")
    result = launchkit(
        "-m", "launchkit.stock.robot_state_publisher.node", "--ros-args", "--params-file", params,
        python=True,
    )  # fmt: skip
    assert_located_error(result, r"params\.yaml:3:\d+", TAGS[tag])


@pytest.mark.parametrize("module", sorted(STOCK_NODES))
def test_every_stock_node_reports_a_tag_in_its_params_file(tmp_path: Path, module: str) -> None:
    params = tmp_path / "params.yaml"
    params.write_text("/**:\n  ros__parameters:\n    p: !!bool maybe\n")
    args = [*STOCK_NODES[module], "--ros-args", "--params-file", str(params)]
    result = launchkit("-m", module, *args, python=True)
    if module == "launchkit.bridge" and importlib.util.find_spec("rclpy") is None:
        # where the real rclpy cannot exist (not CPython 3.11), the bridge stops at that first
        output = result.stdout + result.stderr
        assert result.returncode == 2 and "Traceback" not in output, output
        assert "the ROS 2 bridge needs the real rclpy" in result.stderr.splitlines()[0], output
        return
    assert_located_error(result, r"params\.yaml:3:\d+", "'maybe' is not a valid !!bool")


PYTHON_MISUSE = {
    "DeclareLaunchArgument(['a'])": "the name of DeclareLaunchArgument is a list",
    "GroupAction(['not an action'])": "the actions of GroupAction: a str is not a launch action",
    "LogInfo(msg='hi', condition='true')": "the condition of LogInfo is a str, not a condition",
    "TimerAction(period=1.0, actions=[1])": "the actions of TimerAction: a int is not",
    "Node(package='demo', executable='x', condition=['true'])": "the condition of Node is a",
}


@pytest.mark.parametrize("call", sorted(PYTHON_MISUSE))
def test_misused_python_launch_api(tmp_path: Path, call: str) -> None:
    path = tmp_path / "misuse.launch.py"
    path.write_text(
        "from launch import LaunchDescription\n"
        "from launch.actions import DeclareLaunchArgument, GroupAction, LogInfo, TimerAction\n"
        "from launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([\n"
        f"        {call},\n"
        "    ])\n"
    )
    assert_located_error(launchkit("check", path), r"misuse\.launch\.py:8", PYTHON_MISUSE[call])


@pytest.mark.parametrize(
    ("entity", "line", "message"),
    [
        ("- log:\n    message: \"$(command 'echo a\\0b')\"", 3, "contains a NUL byte"),
        ('- executable:\n    cmd: "echo a\\0b"', 2, "the command line of process 'echo' contains"),
        (
            '- set_env:\n    name: X\n    value: "a\\0b"\n- executable:\n    cmd: "echo ok"',
            5,
            "the environment of process 'echo' contains a NUL byte",
        ),
    ],
)
def test_a_nul_byte_for_a_program(tmp_path: Path, entity: str, line: int, message: str) -> None:
    path = tmp_path / "nul.launch.yaml"
    path.write_text(f"launch:\n{entity}\n")
    result = launchkit("run", path, cwd=tmp_path)
    assert_located_error(result, rf"nul\.launch\.yaml:{line}:\d+", message)
