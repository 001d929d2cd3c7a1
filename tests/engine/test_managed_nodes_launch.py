"""Process tests: lifecycle nodes driven by launch events, and components loaded into
containers through composition_interfaces/srv/LoadNode, as launch_ros does."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from launchkit.testing._isolation import domain_id, free_loopback_port, router_endpoint
from tests.engine.launcher import Launcher
from tests.support import ament_package

LIFECYCLE_TALKER = """
import sys
import launchkit.ros as ros
from launchkit.ros.lifecycle import LifecycleNode, TransitionCallbackReturn


class Talker(LifecycleNode):
    def on_configure(self, state):
        self.get_logger().info('configured')
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        self.get_logger().info('activated')
        return super().on_activate(state)


ros.init(sys.argv)
node = Talker('talker')
try:
    ros.spin(node)
except (KeyboardInterrupt, ros.ExternalShutdownException):
    pass
finally:
    ros.try_shutdown()
"""

LIFECYCLE_LAUNCH = """
import sys

import launch
import lifecycle_msgs.msg
from launch import LaunchDescription
from launch.actions import EmitEvent, LogInfo, RegisterEventHandler
from launch_ros.actions import LifecycleNode, LifecycleTransition
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState


def generate_launch_description():
    talker = LifecycleNode(name='lc_talker', namespace='demo', executable=sys.executable,
                           arguments=['TALKER'], output='screen')
    second = LifecycleNode(name='second', namespace='', executable=sys.executable,
                           arguments=['TALKER'], output='screen')
    return LaunchDescription([
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker, goal_state='inactive',
            entities=[
                LogInfo(msg="'lc_talker' reached 'inactive', activating"),
                EmitEvent(event=ChangeState(
                    lifecycle_node_matcher=launch.events.matches_action(talker),
                    transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE)),
            ])),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker, start_state='activating', goal_state='active',
            entities=[LogInfo(msg="'lc_talker' is active")])),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=second, goal_state='active',
            entities=[LogInfo(msg="'second' is active")])),
        talker,
        second,
        EmitEvent(event=ChangeState(
            lifecycle_node_matcher=launch.events.matches_action(talker),
            transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE)),
        LifecycleTransition(lifecycle_node_names=['second'], transition_ids=[1, 3]),
    ])
"""

EARLY_EXIT_LAUNCH = """
import sys

import launch
import lifecycle_msgs.msg
from launch import LaunchDescription
from launch.actions import EmitEvent
from launch_ros.actions import LifecycleNode
from launch_ros.events.lifecycle import ChangeState


def generate_launch_description():
    node = LifecycleNode(name='early', namespace='', executable=sys.executable,
                         arguments=['-c', 'import sys; sys.exit(1)'], output='screen')
    return LaunchDescription([
        node,
        EmitEvent(event=ChangeState(
            lifecycle_node_matcher=launch.events.matches_action(node),
            transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE)),
    ])
"""

COMPOSITION_LAUNCH = """
from launch import LaunchDescription
from launch_ros.actions import ComposableNodeContainer, LoadComposableNodes
from launch_ros.descriptions import ComposableNode


def generate_launch_description():
    container = ComposableNodeContainer(
        name='box', namespace='', package='PACKAGE', executable='component_container',
        output='screen',
        composable_node_descriptions=[
            ComposableNode(package='composition', plugin='composition::Talker', name='talker',
                           remappings=[('chatter', 'news')]),
        ])
    return LaunchDescription([
        container,
        LoadComposableNodes(target_container=container, composable_node_descriptions=[
            ComposableNode(package='composition', plugin='composition::Listener', name='ear',
                           namespace='robot', remappings=[('chatter', '/news')]),
            ComposableNode(package='nowhere', plugin='nowhere::Nothing', name='ghost'),
        ]),
    ])
"""


@pytest.fixture
def start(tmp_path: Path, launchers: Callable[..., Launcher]) -> Callable[..., Launcher]:
    """``launchkit run`` on a Python launch file, on a router and domain of its own."""

    def run(code: str, env: dict[str, str] | None = None) -> Launcher:
        path = tmp_path / "managed.launch.py"
        path.write_text(code)
        isolation = {
            "LAUNCHKIT_ROUTER": router_endpoint(free_loopback_port()),
            "ROS_DOMAIN_ID": str(domain_id()),
        }
        return launchers(path, env={**isolation, **(env or {})})

    return run


def test_lifecycle_nodes_follow_launch_events(
    start: Callable[..., Launcher], tmp_path: Path
) -> None:
    script = tmp_path / "talker.py"
    script.write_text(LIFECYCLE_TALKER)
    launcher = start(LIFECYCLE_LAUNCH.replace("'TALKER'", repr(str(script))))
    launcher.wait_line("[INFO] [launch.user]: 'lc_talker' is active", timeout=30)
    launcher.wait_line("[INFO] [launch.user]: 'second' is active", timeout=30)
    lines = launcher.lines

    def at(text: str) -> int:
        found = [i for i, line in enumerate(lines) if text in line]
        assert found, f"no line with {text!r} in:\n" + "\n".join(lines)
        return found[0]

    # A node's own lines come through its pipe and the launcher's through Zenoh events: only
    # the order within each channel is causal (the launcher may hear a transition before it
    # reads the line the node printed on the way).
    assert at("[demo.lc_talker]: configured") < at("[demo.lc_talker]: activated")
    assert at("'lc_talker' reached 'inactive'") < at("'lc_talker' is active")
    assert at("[second]: configured") < at("[second]: activated")
    at("'second' is active")
    launcher.signal(2)
    assert launcher.finish() == 0


def test_a_lifecycle_node_that_exits_at_once_ends_the_launch_quietly(
    start: Callable[..., Launcher],
) -> None:
    # The transition's worker waited for the node's service when the launch ended: its
    # context was shut down under it (NotInitializedError in thread launchkit-ros-link).
    launcher = start(EARLY_EXIT_LAUNCH)
    assert launcher.finish() == 0
    assert "process has died" in launcher.text
    assert "Traceback" not in launcher.text and "NotInitializedError" not in launcher.text


def test_components_load_into_a_container(start: Callable[..., Launcher]) -> None:
    launcher = start(COMPOSITION_LAUNCH.replace("PACKAGE", "rclcpp_components"))
    loaded = "[INFO] [launch_ros.actions.load_composable_nodes]: Loaded node"
    launcher.wait_line(f"{loaded} '/talker' in container '/box'", timeout=30)
    launcher.wait_line(f"{loaded} '/robot/ear' in container '/box'", timeout=30)
    failed = launcher.wait_line(
        "Failed to load node 'ghost' of type 'nowhere::Nothing'", timeout=30
    )
    assert failed.startswith("[ERROR] [launch_ros.actions.load_composable_nodes]")
    assert "no launchkit component 'nowhere::Nothing'" in failed
    heard = launcher.wait_line("[robot.ear]: I heard: [Hello World:", timeout=30)
    assert heard.startswith("[component_container-1] ")  # one process holds both components
    assert sum("process started" in line for line in launcher.lines) == 1
    launcher.signal(2)
    assert launcher.finish() == 0


def test_a_ros_package_container_is_loaded_through_its_service(
    start: Callable[..., Launcher], tmp_path: Path
) -> None:
    # An AMENT_PREFIX_PATH package whose container executable is a program of its own (here a
    # script running launchkit's container): launchkit starts it and loads over LoadNode.
    container = (
        f'#!/bin/sh\nexec {sys.executable} -m launchkit.stock.rclcpp_components.container "$@"\n'
    )
    prefix = ament_package(
        tmp_path / "install", "my_components", {"component_container": container}
    )
    env = {
        "AMENT_PREFIX_PATH": os.pathsep.join([str(prefix), os.environ.get("AMENT_PREFIX_PATH", "")])
    }
    launcher = start(COMPOSITION_LAUNCH.replace("PACKAGE", "my_components"), env)
    launcher.wait_line("[INFO] [component_container-1]: process started", timeout=30)
    launcher.wait_line("Loaded node '/talker' in container '/box'", timeout=30)
    launcher.wait_line("Loaded node '/robot/ear' in container '/box'", timeout=30)
    launcher.signal(2)
    assert launcher.finish() == 0
