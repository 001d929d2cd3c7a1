"""Process tests of the Python launch API's event system: handlers run after what they react
to, in ROS's order, with the event's details; OpaqueFunction failures name their line."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.engine.launcher import Launcher

PY = sys.executable

EVENTS = f"""
from launch import LaunchDescription
from launch.actions import (EmitEvent, ExecuteProcess, LogInfo, OpaqueFunction,
                            RegisterEventHandler, TimerAction)
from launch.event_handlers import (OnExecutionComplete, OnProcessExit, OnProcessIO,
                                   OnProcessStart, OnShutdown)
from launch.events import Shutdown
from launch.substitutions import LocalSubstitution


def generate_launch_description():
    worker = ExecuteProcess(
        cmd=['{PY}', '-c', 'print("hello"); import sys; sys.exit(3)'],
        name='worker', output='screen')
    sleeper = ExecuteProcess(cmd=['sleep', '30'], name='sleeper')
    timer = TimerAction(period=0.0, actions=[LogInfo(msg='timer fired')])
    return LaunchDescription([
        RegisterEventHandler(OnProcessStart(target_action=worker, on_start=[
            LogInfo(msg=['worker started as ', LocalSubstitution('event.process_name')])])),
        RegisterEventHandler(OnProcessIO(target_action=worker, on_stdout=lambda event: LogInfo(
            msg='worker said ' + event.text.decode().strip()))),
        RegisterEventHandler(OnExecutionComplete(target_action=timer, on_completion=[
            LogInfo(msg='timer complete')])),
        RegisterEventHandler(OnProcessExit(target_action=sleeper, on_exit=[
            LogInfo(msg=['sleeper exited: ', LocalSubstitution('event.returncode')])])),
        RegisterEventHandler(OnShutdown(on_shutdown=lambda event, context: [
            LogInfo(msg='shutting down because ' + event.reason)])),
        worker,
        sleeper,
        timer,
        RegisterEventHandler(OnProcessExit(target_action=worker, on_exit=lambda event, context: [
            LogInfo(msg=f'worker exited with {{event.returncode}}'),
            EmitEvent(event=Shutdown(reason='the worker is done')),
        ])),
    ])
"""


@pytest.fixture
def launch_py(tmp_path: Path, launchers: Callable[..., Launcher]) -> Callable[..., Launcher]:
    """Start ``launchkit run`` on a Python launch file (see ``launchers``)."""

    def start(code: str, *args: str) -> Launcher:
        path = tmp_path / "events.launch.py"
        path.write_text(code)
        return launchers(path, *args)

    return start


def index_of(lines: list[str], text: str) -> int:
    """The index of the first line containing ``text`` (fails listing the lines)."""
    for index, line in enumerate(lines):
        if text in line:
            return index
    raise AssertionError(f"no line with {text!r} in:\n" + "\n".join(lines))


def indices_of(lines: list[str], *texts: str) -> list[int]:
    """The index of the first line containing each of ``texts``."""
    return [index_of(lines, text) for text in texts]


def test_handlers_react_in_order(launch_py: Callable[..., Launcher]) -> None:
    launcher = launch_py(EVENTS)
    assert launcher.finish() == 0
    lines = launcher.lines
    order = indices_of(
        lines,
        "[INFO] [worker-1]: process started",
        "[INFO] [launch.user]: worker started as worker-1",
        "[worker-1] hello",
        "[INFO] [launch.user]: worker said hello",
        "[ERROR] [worker-1]: process has died",
        "[INFO] [launch.user]: worker exited with 3",
        "[INFO] [launch.user]: shutting down because the worker is done",
        "sending signal 'SIGINT' to process[sleeper-2]",
        "[INFO] [launch.user]: sleeper exited: -2",
    )
    started, on_start, said, heard, died, on_exit, shutdown, signal, sleeper = order
    assert started < on_start and said < heard < died < on_exit < shutdown < signal < sleeper, (
        order,
        lines,
    )
    assert index_of(lines, "timer fired") < index_of(lines, "timer complete")


def test_a_failing_callback_stops_the_launch_naming_its_line(
    launch_py: Callable[..., Launcher],
) -> None:
    code = EVENTS.replace(
        "LogInfo(msg=f'worker exited with {event.returncode}'),",
        "LogInfo(msg=f'worker exited with {event.missing}'),",
    )
    launcher = launch_py(code)
    assert launcher.finish() == 1
    line = next(i for i, text in enumerate(code.splitlines(), 1) if "event.missing" in text)
    error = launcher.wait_line("error: OnProcessExit")
    assert f"events.launch.py:{line}: error: OnProcessExit " in error
    assert "raised AttributeError: 'ProcessExited' object has no attribute 'missing'" in error
    assert "sleeper" in launcher.wait_line("sending signal 'SIGINT'")


def test_on_exit_actions_and_shutdown_process(launch_py: Callable[..., Launcher]) -> None:
    code = f"""
from launch import LaunchDescription
from launch.actions import EmitEvent, ExecuteProcess, LogInfo, Shutdown
from launch.events import matches_action
from launch.events.process import ShutdownProcess


def generate_launch_description():
    sleeper = ExecuteProcess(cmd=['sleep', '30'], name='sleeper',
                             on_exit=[LogInfo(msg='sleeper is gone'), Shutdown(reason='bye')])
    stopper = ExecuteProcess(
        cmd=['{PY}', '-c', 'pass'], name='stopper',
        on_exit=[EmitEvent(event=ShutdownProcess(process_matcher=matches_action(sleeper)))])
    return LaunchDescription([sleeper, stopper])
"""
    launcher = launch_py(code)
    assert launcher.finish() == 0
    lines = launcher.lines
    stopped, signal, gone, required = indices_of(
        lines,
        "[INFO] [stopper-2]: process has finished cleanly",
        "sending signal 'SIGINT' to process[sleeper-1]",
        "[INFO] [launch.user]: sleeper is gone",
        "process[sleeper-1] was required: shutting down launched system",
    )
    assert stopped < signal < gone and signal < required


def test_on_shutdown_hears_ctrl_c_before_processes_are_signalled(
    launch_py: Callable[..., Launcher],
) -> None:
    code = """
from launch import LaunchDescription
from launch.actions import ExecuteProcess, LogInfo, RegisterEventHandler
from launch.event_handlers import OnShutdown
from launch.substitutions import LocalSubstitution


def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=['sleep', '30'], name='sleeper'),
        RegisterEventHandler(OnShutdown(on_shutdown=[LogInfo(
            msg=['Launch was asked to shutdown: ', LocalSubstitution('event.reason')])])),
    ])
"""
    launcher = launch_py(code)
    launcher.wait_line("process started")
    launcher.signal(2)
    assert launcher.finish() == 0
    lines = launcher.lines
    asked = index_of(lines, "[INFO] [launch.user]: Launch was asked to shutdown: ctrl-c (SIGINT)")
    assert asked < index_of(lines, "sending signal 'SIGINT' to process[sleeper-1]")


def test_opaque_functions_run_when_reached(launch_py: Callable[..., Launcher]) -> None:
    code = f"""
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, OpaqueFunction
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessExit


def start_echo(context):
    word = context.launch_configurations['word']
    return [ExecuteProcess(cmd=['{PY}', '-c', f'print("{{word}}")'], name='echo',
                           output='screen')]


def fail_later(context):
    raise RuntimeError('no map for ' + context.launch_configurations['word'])


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('word', default_value='hello'),
        OpaqueFunction(function=start_echo),
        RegisterEventHandler(OnProcessExit(on_exit=[OpaqueFunction(function=fail_later)])),
    ])
"""
    launcher = launch_py(code, "word:=bonjour")
    assert launcher.finish() == 1
    launcher.wait_line("[echo-1] bonjour")
    line = next(i for i, text in enumerate(code.splitlines(), 1) if "raise RuntimeError" in text)
    error = launcher.wait_line("error: OpaqueFunction fail_later()")
    assert (
        f"events.launch.py:{line}: error: OpaqueFunction fail_later() raised RuntimeError: "
        "no map for bonjour" in error
    )


COMPLETION = """
from launch import LaunchDescription
from launch.actions import LogInfo, RegisterEventHandler, SetLaunchConfiguration
from launch.event_handlers import OnExecutionComplete


def generate_launch_description():
    hello = LogInfo(msg='hello')
    setting = SetLaunchConfiguration('word', 'bonjour')
    return LaunchDescription([
        hello,
        setting,
        RegisterEventHandler(OnExecutionComplete(target_action=hello, on_completion=[
            LogInfo(msg='hello is complete')])),
        RegisterEventHandler(OnExecutionComplete(target_action=setting, on_completion=[
            LogInfo(msg='the setting is complete')])),
    ])
"""


def test_completion_reaches_a_handler_registered_after_the_action(
    launch_py: Callable[..., Launcher],
) -> None:
    # the events are queued while the file is visited and delivered afterwards, so a handler
    # registered later still hears them (a check or --print builds no event at all)
    launcher = launch_py(COMPLETION)
    assert launcher.finish() == 0
    lines = launcher.lines
    assert index_of(lines, "[INFO] [launch.user]: hello") < index_of(lines, "hello is complete")
    index_of(lines, "[INFO] [launch.user]: the setting is complete")


def test_a_dry_run_queues_no_event(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # nothing drains a dry run's queue: an event per action would only hold memory
    from launchkit import api
    from launchkit.description.launch_context import LaunchContext

    contexts: list[LaunchContext] = []
    make_context = api._context

    def keep(*args: Any) -> LaunchContext:
        contexts.append(make_context(*args))
        return contexts[-1]

    monkeypatch.setattr(api, "_context", keep)
    path = tmp_path / "completion.launch.py"
    path.write_text(COMPLETION)
    text = api.describe(path)
    assert "event handler OnExecutionComplete(target_action=LogInfo):" in text
    assert "hello is complete" in text and "the setting is complete" in text
    assert len(contexts) == 1 and not contexts[0].event_queue
