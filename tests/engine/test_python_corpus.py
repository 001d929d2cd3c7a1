"""A corpus of public-style Python launch files (``tests/corpus/python``, one per pattern of
ros2/demos, navigation2, ros2_control_demos, turtlebot3, the ROS 2 docs, urdf_tutorial), each
run with ``--print`` against stub packages standing in for the ones not installed."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

from launchkit import api
from launchkit.runtime.recorder import Recorded
from tests.support import ament_package

CORPUS = Path(__file__).resolve().parents[1] / "corpus" / "python"

MINIMAL_URDF = '<robot name="r"><link name="base_link"/></robot>\n'
XACRO = (
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="diffbot">\n'
    '  <xacro:property name="base" value="base_link"/>\n  <link name="${base}"/>\n</robot>\n'
)

#: package -> (executables, {share file: text}); a share file "launch/" links the corpus.
PROGRAM = "#!/bin/sh\nexit 0\n"
STUBS: dict[str, tuple[list[str], dict[str, str]]] = {
    "demo_nodes_cpp": (["talker", "listener"], {}),
    "lifecycle": (["lifecycle_talker", "lifecycle_listener", "lifecycle_service_client"], {}),
    "nav2_bringup": ([], {"params/nav2_params.yaml": "/**:\n  ros__parameters: {}\n"}),
    "nav2_map_server": (["map_server"], {}),
    "nav2_amcl": (["amcl"], {}),
    "nav2_lifecycle_manager": (["lifecycle_manager"], {}),
    "controller_manager": (["ros2_control_node", "spawner"], {}),
    "ros2_control_demo_example_2": ([], {
        "urdf/diffbot.urdf.xacro": XACRO,
        "config/diffbot_controllers.yaml": "controller_manager:\n  ros__parameters: {}\n",
    }),
    "ros2_control_demo_description": ([], {"diffbot/rviz/diffbot.rviz": ""}),
    "turtlebot3_gazebo": ([], {"worlds/turtlebot3_world.world": "<sdf/>\n"}),
    "turtlebot3_description": ([], {"urdf/turtlebot3_burger.urdf": MINIMAL_URDF}),
    "turtlesim": (["turtlesim_node"], {}),
    "urdf_tutorial": ([], {"urdf/01-myfirst.urdf": MINIMAL_URDF, "rviz/urdf.rviz": ""}),
}  # fmt: skip


@pytest.fixture(scope="module")
def stub_packages(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """An ament prefix holding the stub packages, and a ``ros2`` program on the PATH."""
    prefix = tmp_path_factory.mktemp("corpus") / "install"
    for name, (executables, files) in STUBS.items():
        ament_package(prefix, name, dict.fromkeys(executables, PROGRAM), files)
    (prefix / "share" / "nav2_bringup" / "launch").symlink_to(CORPUS)
    _program(prefix / "bin" / "ros2")
    saved = {k: os.environ.get(k) for k in ("AMENT_PREFIX_PATH", "PATH", "USER")}
    os.environ["AMENT_PREFIX_PATH"] = str(prefix)
    os.environ["PATH"] = os.pathsep.join([str(prefix / "bin"), os.environ.get("PATH", "")])
    os.environ.setdefault("USER", "tester")
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


def _program(path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(PROGRAM)
    path.chmod(path.stat().st_mode | stat.S_IEXEC)


def printed(name: str, **arguments: str) -> str:
    """``launchkit run FILE --print`` of a corpus file."""
    return api.describe(CORPUS / name, arguments)


def processes(text: str) -> list[str]:
    """The process names ``--print`` lists, in order (nested ones too)."""
    return [
        line.strip().split(" ", 1)[1].rsplit("  (", 1)[0]
        for line in text.splitlines()
        if line.lstrip().startswith(("node ", "process "))
    ]


EXPECTED = {
    "demos_talker_listener.launch.py": ["talker", "listener"],
    "demos_composition.launch.py": ["component_container"],
    "demos_lifecycle.launch.py": [
        "lifecycle_talker", "lifecycle_listener", "lifecycle_service_client",
    ],
    "nav2_bringup.launch.py": ["map_server", "amcl", "lifecycle_manager"],
    "ros2_control_diffbot.launch.py": [
        "ros2_control_node", "robot_state_publisher", "spawner", "rviz2", "spawner",
    ],
    "turtlebot3_world.launch.py": [
        "gzserver", "gzclient", "robot_state_publisher", "spawn_entity.py",
    ],
    # named as ROS names them: the basename of the one shell word (checked with ros2 launch)
    "event_handlers_tutorial.launch.py": [
        "turtlesim_node", 'Spawn "{x: 2, y: 2, theta: 0.2}"', "sim background_r 120",
    ],
    "opaque_setup.launch.py": ["talker", "talker"],
    "urdf_tutorial_display.launch.py": [
        "joint_state_publisher_gui", "robot_state_publisher", "rviz2",
    ],
}  # fmt: skip


def test_the_corpus_is_complete() -> None:
    files = {p.name for p in CORPUS.glob("*.launch.py")} - {"nav2_localization.launch.py"}
    assert files == set(EXPECTED)


@pytest.mark.parametrize("name", sorted(EXPECTED))
@pytest.mark.usefixtures("stub_packages")
def test_each_file_prints(name: str) -> None:
    assert processes(printed(name)) == EXPECTED[name]


@pytest.mark.usefixtures("stub_packages")
def test_what_the_prints_say() -> None:
    nav2 = printed("nav2_bringup.launch.py", use_sim_time="true")
    assert "/tf:=tf" in nav2 and "--log-level info" in nav2 and "-p use_sim_time:=True" in nav2
    namespaced = printed("nav2_bringup.launch.py", use_namespace="true", namespace="r1")
    assert "-r __ns:=/r1" in namespaced

    control = printed("ros2_control_diffbot.launch.py", gui="false")
    assert "event handler OnProcessExit(target_action=spawner):" in control
    assert '<link name="base_link"/>' in control  # the xacro property was expanded
    assert processes(control).count("rviz2") == 0

    composition = printed("demos_composition.launch.py")
    assert "load composition::Talker (composition) as /talker into /my_container" in composition

    turtlebot = printed("turtlebot3_world.launch.py")
    assert "'gzclient' is not installed: running launchkit's stand-in" in turtlebot
    assert "-x -2.0 -y -0.5" in turtlebot

    tutorial = printed("event_handlers_tutorial.launch.py")
    assert "Launch was asked to shutdown: <event.reason>" in tutorial
    assert "closed the turtlesim window" in tutorial

    opaque = printed("opaque_setup.launch.py", robot_count="3", prefix="x_")
    assert processes(opaque) == ["talker"] * 3 and "__node:=x_talker_2" in opaque

    gui_off = printed("urdf_tutorial_display.launch.py", gui="false")
    assert processes(gui_off)[0] == "joint_state_publisher"


def test_recorded_items_are_plain() -> None:
    # what processes() reads: the render of a nested process is indented under its handler
    from launchkit.runtime.recorder import render

    inner = Recorded("log", text="[INFO] [launch.user]: x")
    assert render([Recorded("handler", text="OnShutdown", inner=[inner])]).splitlines() == [
        "event handler OnShutdown:",
        "  [INFO] [launch.user]: x",
    ]
