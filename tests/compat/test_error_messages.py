"""Errors that say what went wrong and where: a failing ``Command`` child's cause (xacro's
missing file among its warnings), a missing package asked for in ``generate_launch_description``
with the launch file's line, and an error's hint on a line of its own.

What ROS says is recorded beside each test (``ros2_launch.py`` of the reference tools: launch
3.4.3, launch_ros 0.26.6); launchkit says the same in its one-located-line form.
"""

from __future__ import annotations

from pathlib import Path

from tests.compat.conftest import run_launch

ROBOT = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">
{properties}
  <xacro:include filename="$(cwd)/parts1.xacro"/>
  <link name="base"/>
</robot>
"""

PART = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(cwd)/{name}"/>
</robot>
"""

XACRO_LAUNCH = """\
import os
from launch import LaunchDescription
from launch.substitutions import Command
from launch_ros.actions import Node


def generate_launch_description():
    path = os.path.join(os.path.dirname(__file__), 'robot.urdf.xacro')
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': Command(['xacro ', path])}]),
    ])
"""


def test_a_failing_xacro_shows_its_cause_then_its_last_lines(launch_dir: Path) -> None:
    # `ros2 launch x.launch.py` (reference run 2026-11-29, xacro on the PATH): "Caught
    # exception in launch ...: executed command failed. Command: xacro ..." and its whole
    # stderr: 22 pairs of "warning: xacro:property: unknown attribute(s): units" / "when
    # processing file: ...", then "error: No such file or directory: .../missing_wheels.xacro
    # [Errno 2] ...", "when processing file: .../parts5.xacro" and five "included from:" lines
    properties = "\n".join(
        f'  <xacro:property name="wheel_{i}" value="0.{i}" units="m"/>' for i in range(1, 23)
    )
    (launch_dir / "robot.urdf.xacro").write_text(ROBOT.format(properties=properties))
    for index in range(1, 5):
        (launch_dir / f"parts{index}.xacro").write_text(PART.format(name=f"parts{index + 1}.xacro"))
    (launch_dir / "parts5.xacro").write_text(PART.format(name="missing_wheels.xacro"))
    (launch_dir / "x.launch.py").write_text(XACRO_LAUNCH)
    ran = run_launch(launch_dir, "x.launch.py")
    assert ran.status != 0, ran.text
    missing = launch_dir / "missing_wheels.xacro"
    start = next(i for i, line in enumerate(ran.lines) if "x.launch.py:11: error:" in line)
    assert ran.lines[start].endswith(
        "failed with exit code 2; its first error and the last 4 of its 51 lines on stderr:"
    ), ran.text
    assert ran.lines[start + 1 :] == [
        f"  | error: No such file or directory: {missing} [Errno 2] No such file or directory: "
        f"'{missing}'",
        "  | ...",
        f"  | included from: {launch_dir}/parts3.xacro",
        f"  | included from: {launch_dir}/parts2.xacro",
        f"  | included from: {launch_dir}/parts1.xacro",
        f"  | included from: {launch_dir}/robot.urdf.xacro",
    ]


FIND = """\
from launch import LaunchDescription
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('no_such_pkg').find('no_such_pkg')
    return LaunchDescription([])
"""


def test_find_package_share_find_names_the_launch_file_and_line(launch_dir: Path) -> None:
    # `ros2 launch find.launch.py` (reference run 2026-11-29): "Caught multiple exceptions when
    # trying to load file of format [py]: - PackageNotFoundError: "package 'no_such_pkg' not
    # found, searching: [...]"", exit status 1
    path = launch_dir / "find.launch.py"
    path.write_text(FIND)
    ran = run_launch(launch_dir, "find.launch.py", env={"AMENT_PREFIX_PATH": ""})
    assert ran.status == 2, ran.text
    assert ran.lines[0].startswith(f"{path}:6: error: package 'no_such_pkg' not found"), ran.text
    assert ran.lines[1].startswith("  hint: searched ")


LATER = """\
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import OpaqueFunction, TimerAction


def setup(context):
    get_package_share_directory('no_such_pkg')


def generate_launch_description():
    return LaunchDescription([TimerAction(period=0.1, actions=[OpaqueFunction(function=setup)])])
"""


def test_an_error_while_running_shows_its_hint_on_a_line_of_its_own(launch_dir: Path) -> None:
    # `ros2 launch later.launch.py` (reference run 2026-11-29): "[ERROR] [launch]: Caught
    # exception in launch (see debug for traceback): "package 'no_such_pkg' not found,
    # searching: [...]"", exit status 1
    path = launch_dir / "later.launch.py"
    path.write_text(LATER)
    ran = run_launch(launch_dir, "later.launch.py", env={"AMENT_PREFIX_PATH": ""})
    assert ran.status == 1, ran.text
    error = next(i for i, line in enumerate(ran.lines) if line.startswith("[ERROR]"))
    assert ran.lines[error].startswith(
        f"[ERROR] [launch]: {path}:7: error: package 'no_such_pkg' not found (expected "
    ), ran.text
    assert ran.lines[error + 1].startswith("  hint: searched entry points"), ran.text
    assert "\\n" not in ran.text
