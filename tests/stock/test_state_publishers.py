"""robot_state_publisher and joint_state_publisher as real processes on the ROS layer."""

from __future__ import annotations

import os
import signal
from pathlib import Path
from typing import Any

import pytest
import yaml
from launchkit.ros.msgs.sensor_msgs.msg import JointState
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

import launchkit.ros as ros
from launchkit.stock.urdf import parse_urdf
from tests.stock.conftest import Processes, latched, spin_until

URDF = (Path(__file__).parents[2] / "urdf" / "three_wheeled_robot.urdf").read_text()
RSP = "launchkit.stock.robot_state_publisher.node"
JSP = "launchkit.stock.joint_state_publisher.node"


def _params(tmp_path: Path, **params: Any) -> str:
    path = tmp_path / "params.yaml"
    path.write_text(yaml.safe_dump({"/**": {"ros__parameters": params}}))
    return str(path)


def test_rsp_latches_description_and_fixed_joints_and_sends_moving_ones(
    tmp_path: Path, processes: Processes, probe: Any
) -> None:
    processes.start(
        RSP,
        "--ros-args",
        "--params-file",
        _params(tmp_path, robot_description=URDF, frame_prefix="r1/"),
    )
    descriptions: list[Any] = []
    statics: list[Any] = []
    dynamic: list[Any] = []
    probe.create_subscription(String, "/robot_description", descriptions.append, latched())
    probe.create_subscription(TFMessage, "/tf_static", statics.append, latched())
    probe.create_subscription(TFMessage, "/tf", dynamic.append, 10)
    spin_until(probe, lambda: bool(descriptions and statics), "latched description and tf_static")
    assert descriptions[0].data == URDF
    static = {t.child_frame_id: t for t in statics[0].transforms}
    assert sorted(static) == ["r1/camera", "r1/lidar"]
    assert static["r1/lidar"].header.frame_id == "r1/base"
    assert static["r1/lidar"].transform.translation.x == pytest.approx(-0.285)

    joints = probe.create_publisher(JointState, "/joint_states", 10)
    state = JointState(name=["wheel_left_joint"], position=[1.0])
    spin_until(
        probe, lambda: bool(dynamic), "/tf after /joint_states", each=lambda: joints.publish(state)
    )
    [moved] = dynamic[0].transforms
    expected = parse_urdf(URDF).moving_transforms({"wheel_left_joint": 1.0})[0]
    assert (moved.header.frame_id, moved.child_frame_id) == ("r1/base", "r1/wheel_left_link")
    rotation = moved.transform.rotation
    assert (rotation.x, rotation.y, rotation.z, rotation.w) == pytest.approx(expected.rotation)


@pytest.mark.parametrize(
    ("description", "message"),
    [("", "parameter robot_description is empty"), ("<robot name='x'><link", "not well-formed")],
)
def test_rsp_bad_description_is_one_line_exit_2(
    tmp_path: Path, processes: Processes, description: str, message: str
) -> None:
    proc = processes.start(
        RSP, "--ros-args", "--params-file", _params(tmp_path, robot_description=description)
    )
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 2, err
    assert message in err
    assert "Traceback" not in err
    (line,) = [line for line in err.splitlines() if "error:" in line]
    assert line.startswith("robot_state_publisher: ") and ": error: " in line


def test_jsp_publishes_zeros_and_merges_sources(
    tmp_path: Path, processes: Processes, probe: Any
) -> None:
    processes.start(
        JSP,
        "--ros-args",
        "--params-file",
        _params(
            tmp_path,
            robot_description=URDF,
            rate=20.0,
            source_list=["/wheel_source"],
            zeros={"caster_joint": 0.25},
        ),
    )
    states: list[Any] = []
    probe.create_subscription(JointState, "/joint_states", states.append, 10)
    spin_until(probe, lambda: bool(states), "/joint_states")
    assert list(states[0].name) == ["wheel_right_joint", "wheel_left_joint", "caster_joint"]
    assert list(states[0].position) == [0.0, 0.0, 0.25]

    source = probe.create_publisher(JointState, "/wheel_source", 10)
    update = JointState(name=["wheel_left_joint", "not_ours"], position=[1.5, 9.0])
    spin_until(
        probe,
        lambda: list(states[-1].position) == [0.0, 1.5, 0.25],
        "a merged source position on /joint_states",
        each=lambda: source.publish(update),
    )


def test_jsp_waits_for_the_description_topic(processes: Processes, probe: Any) -> None:
    processes.start(JSP)
    states: list[Any] = []
    probe.create_subscription(JointState, "/joint_states", states.append, 10)
    description = probe.create_publisher(String, "/robot_description", latched())
    description.publish(String(data=URDF))
    spin_until(probe, lambda: bool(states), "/joint_states from the description topic")
    assert "wheel_left_joint" in list(states[0].name)


def test_jsp_gui_publishes_the_positions_of_its_sliders(
    tmp_path: Path, processes: Processes, probe: Any
) -> None:
    """The GUI's sliders live in the viewer page, which publishes their positions on the node's
    ~/slider_positions; the node puts them on /joint_states as its Tk window would."""
    proc = processes.start(
        "launchkit.cli",
        "exec",
        "joint_state_publisher_gui",
        "joint_state_publisher_gui",
        "--ros-args",
        "--params-file",
        _params(tmp_path, robot_description=URDF),
    )
    states: list[Any] = []
    probe.create_subscription(JointState, "/joint_states", states.append, 10)
    spin_until(probe, lambda: bool(states), "/joint_states from joint_state_publisher_gui")
    assert list(states[0].position) == [0.0, 0.0, 0.0]
    assert "joint_state_publisher_gui" in probe.get_node_names()
    sliders = probe.create_publisher(JointState, "/joint_state_publisher_gui/slider_positions", 10)
    moved = JointState(name=["wheel_left_joint"], position=[1.25])
    spin_until(
        probe,
        lambda: (
            bool(states)
            and dict(zip(states[-1].name, states[-1].position, strict=True))["wheel_left_joint"]
            == 1.25
        ),
        "/joint_states with the slider's wheel_left_joint position 1.25",
        each=lambda: sliders.publish(moved),
    )
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=15)
    assert proc.returncode == 0, err
    assert "/joint_state_publisher_gui/slider_positions" in err


SMALL = (
    "<robot name='small'><link name='base'/><link name='mast'/>"
    "<joint name='mast_joint' type='fixed'><parent link='base'/><child link='mast'/>"
    "<origin xyz='0 0 1'/></joint></robot>"
)


def _set_description(probe: Any, value: str) -> Any:
    """Set robot_state_publisher's robot_description through its parameter service."""
    from launchkit.ros.msgs import get_message, get_service

    srv = get_service("rcl_interfaces/srv/SetParameters")
    client = probe.create_client(srv, "/robot_state_publisher/set_parameters")
    assert client.wait_for_service(timeout_sec=15.0), "robot_state_publisher's parameter service"
    value_msg = ros.Parameter("robot_description", value=value).to_msg_value()
    param = get_message("rcl_interfaces/msg/Parameter")(name="robot_description", value=value_msg)
    future = client.call_async(srv.Request(parameters=[param]))
    spin_until(probe, future.done, "the set_parameters answer")
    return future.result().results[0]


def test_rsp_takes_a_new_valid_description_at_run_time(
    tmp_path: Path, processes: Processes, probe: Any
) -> None:
    processes.start(RSP, "--ros-args", "--params-file", _params(tmp_path, robot_description=URDF))
    descriptions: list[Any] = []
    statics: list[Any] = []
    probe.create_subscription(String, "/robot_description", descriptions.append, latched())
    probe.create_subscription(TFMessage, "/tf_static", statics.append, latched())
    spin_until(probe, lambda: bool(descriptions and statics), "the first description")

    bad = "<robot name='bad'><link name='a'/><joint name='j' type='hinge'/></robot>"
    rejected = _set_description(probe, bad)
    assert not rejected.successful
    assert "joint 'j' has type 'hinge'" in rejected.reason

    accepted = _set_description(probe, SMALL)
    assert accepted.successful, accepted.reason
    spin_until(probe, lambda: descriptions[-1].data == SMALL, "the new description")
    spin_until(
        probe,
        lambda: [t.child_frame_id for t in statics[-1].transforms] == ["mast"],
        "the new robot's fixed transforms",
    )
    assert len(descriptions) == 2  # the rejected one was never published
