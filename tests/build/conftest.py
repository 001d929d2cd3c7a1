"""The workspace most build tests look at, built once: a plain Python package with a console
script, a launch file and a parameters file; an interface package (msg, srv, action); a
Python package depending on both; a C++ package and a package depending on it (both
skipped); an ignored folder."""

from __future__ import annotations

import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from workspaces import (
    cpp_package,
    environment,
    interface_package,
    launchkit_build,
    python_package,
    write_package,
)

TALK = """\
import sys


def main():
    print("talk:", " ".join(sys.argv[1:]), flush=True)
    if sys.argv[1:] and sys.argv[1].endswith(".yaml"):
        with open(sys.argv[1]) as params:
            print(params.read().strip(), flush=True)
"""
LAUNCH = """\
<launch>
  <node pkg="talker_py" exec="talk" name="talk" output="screen"
        args="$(find-pkg-share talker_py)/config/talk.yaml"/>
</launch>
"""
LAUNCH_PY = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    params = os.path.join(get_package_share_directory('talker_py'), 'config', 'talk.yaml')
    return LaunchDescription([
        Node(package='talker_py', executable='talk', name='talk', output='screen',
             arguments=[params]),
    ])
"""
PARAMS = "talk:\n  ros__parameters:\n    greeting: hi from the params file\n"
INTERFACES = {
    "msg/Num.msg": "int64 num\n",
    "srv/AddThree.srv": "int64 a\nint64 b\nint64 c\n---\nint64 sum\n",
    "action/Count.action": "int32 order\n---\nint32[] sequence\n---\nint32[] partial\n",
}


@dataclass
class Built:
    """The built workspace: its folder, the build's output and the time it took."""

    root: Path
    home: Path
    result: subprocess.CompletedProcess[str]
    seconds: float

    @property
    def install(self) -> Path:
        """The install folder."""
        return self.root / "install"


@pytest.fixture(scope="package")
def built(tmp_path_factory: pytest.TempPathFactory) -> Built:
    """The workspace above, after `launchkit build`."""
    root = tmp_path_factory.mktemp("ws")
    home = tmp_path_factory.mktemp("home")
    src = root / "src"
    talker = python_package("talker_py", {"talk": TALK}, {"exec_depend": ["rclpy", "std_msgs"]})
    talker["launch/talk.launch.xml"] = LAUNCH
    talker["launch/talk.launch.py"] = LAUNCH_PY
    talker["config/talk.yaml"] = PARAMS
    write_package(src, "talker_py", talker)
    write_package(
        src, "interfaces/demo_interfaces", interface_package("demo_interfaces", INTERFACES)
    )
    user = python_package(
        "demo_user",
        {"use": 'def main():\n    print("demo_user runs")\n'},
        {"exec_depend": ["talker_py", "demo_interfaces", "python3-numpy"]},
    )
    write_package(src, "demo_user", user)
    write_package(src, "cpp/demo_cpp", cpp_package("demo_cpp"))
    write_package(
        src,
        "demo_cpp_user",
        python_package(
            "demo_cpp_user", {"run": "def main():\n    pass\n"}, {"depend": ["demo_cpp"]}
        ),
    )
    ignored = write_package(src, "ignored/talker_py", python_package("talker_py", {}))
    (ignored.parent / "COLCON_IGNORE").touch()  # a second talker_py: no clash, it is ignored
    started = time.monotonic()
    result = launchkit_build(root, env=environment(home))
    return Built(root, home, result, time.monotonic() - started)
