"""A YAML launch file run end to end: its processes start with the environment, names and
parameters it gives them, a node talks on the ROS layer in the namespace it was pushed into,
a timer's process starts later, and Ctrl-C leaves nothing behind."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

LAUNCH = """\
launch:
- arg: {name: robot, default: r1}
- set_env: {name: GREETING, value: hello}
- executable:
    cmd: sh -c 'echo greeting=$GREETING extra=$EXTRA; exec sleep 60'
    name: greeter
    output: screen
    env: [{name: EXTRA, value: from the env list}]
- group:
  - push_ros_namespace: {namespace: $(var robot)}
  - node:
      pkg: robot_state_publisher
      exec: robot_state_publisher
      name: rsp
      output: screen
      param:
      - name: robot_description
        value: $(command 'cat $(find-pkg-share robot_wheel)/urdf/three_wheeled_robot.urdf')
      - {name: frame_prefix, value: $(var robot)/}
      - {name: publish_frequency, value: 20.0}
- timer:
    period: 0.3
    children:
    - executable: {cmd: "sh -c 'echo timer fired for $(var robot)'", name: late, output: screen}
"""


@pytest.fixture(scope="module")
def robot(launch_module, tmp_path_factory: pytest.TempPathFactory) -> Any:  # type: ignore[no-untyped-def]
    """The YAML launch with robot:=r2, shared by the tests of this module."""
    path = Path(tmp_path_factory.mktemp("yaml_launch")) / "robot.launch.yaml"
    path.write_text(LAUNCH)
    return launch_module(path, args={"robot": "r2"}, ready_timeout=60)


def test_executable_gets_its_environment(robot: Any) -> None:
    line = robot.process("greeter").wait_output("greeting=", timeout=30)
    assert line == "greeting=hello extra=from the env list"


def test_node_runs_in_its_namespace_with_typed_parameters(robot: Any) -> None:
    (description,) = robot.expect_topic("/r2/robot_description", within=30)
    assert isinstance(description, String)
    assert '<robot name="three_wheeled_robot">' in description.data
    (static,) = robot.expect_topic("/tf_static", within=30)
    assert isinstance(static, TFMessage)
    assert {t.child_frame_id for t in static.transforms} == {"r2/camera", "r2/lidar"}


def test_timer_starts_its_process_later(robot: Any) -> None:
    late = robot.process("late")
    assert late.wait_output("timer fired", timeout=30) == "timer fired for r2"
    assert late.wait_exit(timeout=30) == 0


def test_ctrl_c_stops_everything(robot: Any) -> None:
    # runs last in the module: stop() also checks that no process of the launch survived.
    # xdist may run it on a worker of its own, with a fresh launch: wait for the timer's
    # process here too rather than count on test_timer_starts_its_process_later
    robot.process("greeter").wait_running(timeout=30)
    assert robot.process("late").wait_exit(timeout=30) == 0
    result = robot.stop()
    result.assert_exit_codes({"late": 0, "*": {0, -2}})
    assert result.returncode == 0
