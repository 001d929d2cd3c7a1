"""The YAML corpus (``tests/corpus/yaml``): launch files written the way public ROS 2 projects
write them, each run with ``launchkit run --print``. Packages launchkit does not ship (the demo
nodes, joy, teleop_twist_joy, rosbridge) are stubs in an ``AMENT_PREFIX_PATH`` prefix, as a
ROS user's workspace would provide them."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.engine.launcher import run_launchkit as launchkit
from tests.support import ament_package

CORPUS = Path(__file__).parents[1] / "corpus" / "yaml"

STUBS = {
    "demo_nodes_cpp": ("talker", "listener"),
    "joy": ("joy_node",),
    "teleop_twist_joy": ("teleop_node",),
    "rosbridge_server": ("rosbridge_websocket",),
    "rosapi": ("rosapi_node",),
}

#: (file, arguments) -> what --print must show (text, or a pattern where launch_ros allows two
#: spellings: a global parameter may go in a params file or a -p argument)
EXPECTED: dict[tuple[str, tuple[str, ...]], list[str | re.Pattern[str]]] = {
    ("talker_listener.launch.yaml", ()): [
        "lib/demo_nodes_cpp/talker",
        "lib/demo_nodes_cpp/listener --ros-args -r chatter:=/chatter",
    ],
    ("robot_bringup.launch.yaml", ()): [
        '<robot name="three_wheeled_robot">',
        "use_sim_time: false",
        "publish_frequency: 30.0",
        "-r __node:=joint_state_publisher",
        "rate: 10",
        "- /wheel_states",
    ],
    ("teleop_joy.launch.yaml", ("joy_vel:=/robot/cmd_vel",)): [
        "-r __node:=joy_node",
        "device_id: 0",
        "deadzone: 0.3",
        "autorepeat_rate: 20.0",
        f"--params-file {CORPUS}/config/ps3.config.yaml",
        "publish_stamped_twist: false",
        "-r /cmd_vel:=/robot/cmd_vel",
    ],
    ("rosbridge_websocket.launch.yaml", ()): [
        "port: 9090",
        "address: ''",
        "retry_startup_delay: 5.0",
        "max_message_size: 10000000",
        "topics_glob: ''",
        "use_compression: false",
        "-r __node:=rosapi",
    ],
    ("rosbridge_websocket.launch.yaml", ("ssl:=true", "certfile:=/etc/ssl/bridge.pem")): [
        "certfile: /etc/ssl/bridge.pem",
        "port: 9090",
    ],
    ("multi_robot.launch.yaml", ()): [
        "__ns:=/alpha",
        "__ns:=/beta",
        "-r /tf:=tf",
        "frame_prefix: alpha/",
        "frame_prefix: beta/",
        "cmd: echo spawning alpha at x=0.0",
        "cmd: echo spawning beta at x=2.0",
        re.compile(r"use_sim_time(: |:=)[Tt]rue"),  # -p writes Python's True, as launch_ros
        "env: ROBOT_NAMES=alpha,beta",
        "timer after 3 s:",
        "[INFO] [launch.user]: robots up: alpha,beta",
    ],
    ("robot_instance.launch.yaml", ("robot_name:=solo",)): [
        "frame_prefix: solo/",
        "cmd: echo spawning solo at x=0.0",
    ],
    ("mixed_frontends.launch.yaml", ()): [
        "[INFO] [launch.user]: xml says: hello",
        "cmd: echo hello",
        "[INFO] [launch.user]: python says: hello from yaml",
        "lib/demo_nodes_cpp/listener --ros-args -r chatter:=/chatter",
    ],
}


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An install prefix with a stub executable for each package launchkit does not ship."""
    prefix = tmp_path_factory.mktemp("stub_install")
    for package, executables in STUBS.items():
        ament_package(prefix, package, dict.fromkeys(executables, '#!/bin/sh\necho "$0 $*"\n'))
    return prefix


def test_every_corpus_file_is_covered() -> None:
    files = {path.name for path in CORPUS.glob("*.launch.yaml")}
    assert files == {name for name, _ in EXPECTED}


@pytest.mark.parametrize(("name", "args"), list(EXPECTED), ids=lambda v: str(v))
def test_corpus_file_prints(
    workspace: Path, tmp_path: Path, name: str, args: tuple[str, ...]
) -> None:
    result = launchkit(
        "run",
        "--print",
        str(CORPUS / name),
        *args,
        cwd=tmp_path,
        env={"AMENT_PREFIX_PATH": str(workspace), "ROS_LOG_DIR": str(tmp_path / "log")},
    )
    assert result.returncode == 0, result.stderr
    for expected in EXPECTED[(name, args)]:
        found = (
            expected.search(result.stdout)
            if isinstance(expected, re.Pattern)
            else expected in result.stdout
        )
        assert found, f"{expected!r} not in:\n{result.stdout}"


def test_rosbridge_starts_one_bridge_by_its_condition(workspace: Path, tmp_path: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(workspace), "ROS_LOG_DIR": str(tmp_path / "log")}
    path = str(CORPUS / "rosbridge_websocket.launch.yaml")
    plain = launchkit("run", "--print", path, cwd=tmp_path, env=env).stdout
    secure = launchkit("run", "--print", path, "ssl:=true", cwd=tmp_path, env=env).stdout
    assert plain.count("lib/rosbridge_server/rosbridge_websocket") == 1
    assert "certfile" not in plain
    assert secure.count("lib/rosbridge_server/rosbridge_websocket") == 1
