"""Command lines of the gazebo_ros executables, and bad input giving exit status 2, no traceback."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from launchkit.packages import PackageIndex
from launchkit.stock.gazebo_ros.camera_node import CameraNodeParams
from launchkit.stock.gazebo_ros.plugin_processes import (
    CAMERA_MODULE,
    DIFF_DRIVE_MODULE,
    PluginProcesses,
    plugin_command,
)
from launchkit.stock.gazebo_ros.server_options import UsageError, parse_server_args
from launchkit.stock.gazebo_ros.sim.diff_drive import DiffDriveParams
from launchkit.stock.gazebo_ros.sim.model import PluginSpec, RosOptions
from launchkit.stock.gazebo_ros.spawn_entity import SpawnError, parse_args


def test_seed_gazebo_command_line_is_accepted() -> None:
    options = parse_server_args(
        ["--verbose", "-s", "libgazebo_ros_init.so", "-s", "libgazebo_ros_factory.so"]
    )
    assert options.verbose and options.ros_init and options.factory
    assert options.world == "empty" and not options.gui


def test_server_plugins_are_honoured_and_ros_args_split_off() -> None:
    options = parse_server_args(
        ["-s", "libgazebo_ros_init.so", "obstacles", "--ros-args", "-p", "x:=1"]
    )
    assert options.ros_init and not options.factory and options.world == "obstacles"
    # gazebo.launch.py switches a plugin off with '-s none'
    options = parse_server_args(["-s", "none", "-s", "libgazebo_ros_factory.so", ""])
    assert options.factory and not options.ros_init and options.world == "empty"
    with pytest.raises(UsageError, match="unrecognized"):
        parse_server_args(["--bogus"])


def test_spawn_entity_arguments() -> None:
    args = parse_args(["-topic", "robot_description", "-entity", "bot", "-z", "0.2", "-Y", "1.5"])
    assert (args.topic, args.entity, args.z, args.Y, args.x) == (
        "robot_description",
        "bot",
        0.2,
        1.5,
        0.0,
    )
    with pytest.raises(SpawnError, match="-entity"):
        parse_args(["-file", "x.urdf"])
    with pytest.raises(SpawnError, match="not allowed with"):
        parse_args(["-file", "x.urdf", "-topic", "t", "-entity", "e"])


@pytest.mark.parametrize(
    ("executable", "argv", "message"),
    [
        ("gazebo", ["no_such_world"], "world 'no_such_world' not found"),
        ("spawn_entity.py", ["-file", "x.urdf"], "-entity"),
        ("spawn_entity.py", ["-entity", "e", "-x", "left", "-file", "f"], "invalid float value"),
        ("diff_drive", [], "parameter 'entity' is required"),
        ("diff_drive", ["--ros-args", "-p", "entity:=bot"], "<left_joint> is required"),
        ("camera", [], "parameters 'entity' and 'model' (URDF text) are required"),
        (
            "camera",
            [
                "--ros-args",
                "-p",
                "entity:=bot",
                "-p",
                "model:=<robot name='r'><link name='b'/></robot>",
            ],
            "the model has no camera sensor",
        ),
    ],
)
def test_bad_command_lines_exit_2_with_one_error(
    executable: str, argv: list[str], message: str, router: str
) -> None:
    command = PackageIndex().executable("gazebo_ros", executable)
    # a router to join: the plugin nodes read their parameters once their node is up (without
    # one, a node waits for a router a few seconds before it goes on without)
    result = subprocess.run(
        [*command, *argv], capture_output=True, text=True, timeout=60, check=False
    )
    assert result.returncode == 2
    (line,) = [line for line in result.stderr.splitlines() if "error:" in line]
    assert line.startswith(f"{executable}: error: ") and message in line
    assert "Traceback" not in result.stderr


def test_diff_drive_child_command_line(tmp_path: Path) -> None:
    plugin = PluginSpec(
        "libgazebo_ros_diff_drive.so",
        "base_controller",
        {},
        RosOptions("robot1", (("cmd_vel", "cmd_demo"),)),
    )
    params = DiffDriveParams("l", "r", wheel_separation=0.5)
    params_file = tmp_path / "p.yaml"
    argv = plugin_command(
        DIFF_DRIVE_MODULE, "bot", plugin, params.as_parameters(), params_file, remap=True
    )
    assert argv[:3] == [sys.executable, "-m", "launchkit.stock.gazebo_ros.diff_drive_node"]
    assert argv[3:] == [
        "--ros-args",
        "-r",
        "__node:=base_controller",
        "-r",
        "__ns:=/robot1",
        "--params-file",
        str(params_file),
        "-r",
        "cmd_vel:=cmd_demo",
    ]
    values = yaml.safe_load(params_file.read_text())["/**"]["ros__parameters"]
    assert values["entity"] == "bot" and values["wheel_separation"] == 0.5
    assert DiffDriveParams.from_parameters(values) == params


def test_camera_child_command_line(tmp_path: Path) -> None:
    plugin = PluginSpec(
        "libgazebo_ros_camera.so",
        "camera_controller",
        {},
        RosOptions("robot1", (("image_raw", "image"),)),
    )
    params = CameraNodeParams("camera1", "<robot/>", "/worlds/obstacles.world", egl=False)
    params_file = tmp_path / "p.yaml"
    argv = plugin_command(
        CAMERA_MODULE, "bot", plugin, params.as_parameters(), params_file, remap=False
    )
    assert argv == [
        sys.executable,
        "-m",
        "launchkit.stock.gazebo_ros.camera_node",
        "--ros-args",
        "-r",
        "__node:=camera_controller",
        "-r",
        "__ns:=/robot1",
        "--params-file",
        str(params_file),
    ]  # the remapping is already in the camera's topic names (CameraConfig)
    values = yaml.safe_load(params_file.read_text())["/**"]["ros__parameters"]
    assert values == {"entity": "bot", **params.as_parameters()}


def test_a_launch_keeps_the_plugin_parameter_files_for_the_launcher_to_remove(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A camera node the launcher starts just before a Ctrl-C reads its file after the server
    # has stopped: under a launch the files stay until the launcher removes its folder.
    monkeypatch.setenv("LAUNCHKIT_RUN_TMPDIR", str(tmp_path))
    in_launch = PluginProcesses(log=print)
    assert in_launch._folder.parent == tmp_path
    in_launch.stop()
    assert in_launch._folder.is_dir()
    monkeypatch.delenv("LAUNCHKIT_RUN_TMPDIR")
    alone = PluginProcesses(log=print)
    alone.stop()
    assert not alone._folder.exists()
