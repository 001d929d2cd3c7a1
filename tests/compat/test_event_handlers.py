"""Event handlers as in Jazzy: their functions run only on their events (never in ``--print``
or ``check``), OnShutdown handlers run when a launch ends because everything exited
(``Shutdown(reason='idle')``), and ``ExecuteProcess(on_exit=...)`` takes a function.

Expectations were recorded from the real launch (``ros2_launch.py`` of the reference tools:
launch 3.4.3, launch_ros 0.26.6) on the same files; each test names its run.
"""

from __future__ import annotations

from pathlib import Path

from tests.compat.conftest import run_launch, run_launchkit

HANDLERS = """\
import os
import sys

import launch
from launch import LaunchDescription
from launch.actions import (DeclareLaunchArgument, ExecuteProcess, LogInfo, OpaqueFunction,
                            RegisterEventHandler)
from launch.event_handlers import OnProcessExit, OnProcessIO, OnShutdown
from launch.substitutions import LaunchConfiguration

MARKER = os.path.join(os.path.dirname(__file__), 'marker')


def remember(what):
    with open(MARKER, 'a') as stream:
        stream.write(what + '\\n')


def exited(event, context):
    remember('exited %d' % event.returncode)
    return [LogInfo(msg='worker exited')]


def generate_launch_description():
    worker = ExecuteProcess(cmd=[sys.executable, '-c', 'print("working")'], name='worker',
                            output='screen', on_exit=lambda event, context: remember('on_exit'))
    return LaunchDescription([
        DeclareLaunchArgument('who', default_value='me'),
        worker,
        RegisterEventHandler(OnProcessIO(target_action=worker,
                                         on_stdout=lambda event: remember('io'))),
        RegisterEventHandler(OnProcessExit(target_action=worker, on_exit=exited)),
        RegisterEventHandler(OnShutdown(on_shutdown=[
            OpaqueFunction(function=lambda context: os.remove(MARKER + '.missing')),
        ])),
        RegisterEventHandler(OnShutdown(on_shutdown=[
            LogInfo(msg=['shutting down, who=', LaunchConfiguration('who')],
                    condition=launch.Condition(
                        predicate=lambda context: remember('predicate') or True)),
            OpaqueFunction(function=lambda context: remember('shutdown')),
        ])),
    ])
"""


def test_print_and_check_never_call_what_runs_on_events(launch_dir: Path) -> None:
    # `ros2 launch -p handlers.launch.py` (ros2launch's print_a_launch_file, reference run
    # 2026-11-29) prints the description and calls none of the file's handler functions: no
    # marker is written and the OpaqueFunction that would fail is not run
    path = launch_dir / "handlers.launch.py"
    path.write_text(HANDLERS)
    printed = run_launch(launch_dir, "--print", str(path))
    assert printed.status == 0, printed.text
    assert not (launch_dir / "marker").exists()
    text = printed.text
    assert f"event handler on_exit of worker:\n  calls <lambda>  ({path}:26)" in text
    assert f"event handler OnProcessIO(target_action=worker):\n  calls <lambda>  ({path}:31)" in (
        text
    )
    assert f"event handler OnProcessExit(target_action=worker):\n  calls exited  ({path}:19)" in (
        text
    )
    assert f"event handler OnShutdown:\n  calls <lambda> (OpaqueFunction)  ({path}:34)" in text
    assert f"calls <lambda> (a condition)  ({path}:38)" in text


def test_check_never_calls_what_runs_on_events(launch_dir: Path) -> None:
    # as above: ROS calls a handler's function only on its event
    (launch_dir / "handlers.launch.py").write_text(HANDLERS)
    checked = run_launchkit(launch_dir, "check", "handlers.launch.py")
    assert checked.status == 0, checked.text
    assert "ok (1 file(s)" in checked.text
    assert not (launch_dir / "marker").exists()


def test_handler_functions_run_on_their_events(launch_dir: Path) -> None:
    # `ros2 launch handlers.launch.py` (reference run 2026-11-29): the worker's line, then
    # "worker exited", "shutting down, who=me" (the newest OnShutdown handler first), then the
    # older handler's OpaqueFunction fails: exit status 1. The marker holds, in order: io,
    # exited 0, on_exit, predicate, shutdown (ROS may call on_stdout once per chunk read)
    (launch_dir / "handlers.launch.py").write_text(HANDLERS)
    ran = run_launch(launch_dir, "handlers.launch.py")
    assert ran.status == 1, ran.text
    assert ran.launch_lines()[:5] == [
        "[INFO] [worker-1]: process started with pid [N]",
        "[worker-1] working",
        "[INFO] [worker-1]: process has finished cleanly [pid N]",
        "[INFO] [launch.user]: worker exited",
        "[INFO] [launch.user]: shutting down, who=me",
    ]
    assert (
        "No such file or directory" in ran.lines[-1] and "handlers.launch.py:34" in (ran.lines[-1])
    )
    calls = (launch_dir / "marker").read_text().split("\n")
    assert [c for c in calls if c and c != "io"] == [
        "exited 0",
        "on_exit",
        "predicate",
        "shutdown",
    ]
    assert calls[0] == "io"


IDLE = """\
import sys
from launch import LaunchDescription
from launch.actions import ExecuteProcess, LogInfo, OpaqueFunction, RegisterEventHandler
from launch.event_handlers import OnProcessExit, OnShutdown
from launch.substitutions import LocalSubstitution


def generate_launch_description():
    worker = ExecuteProcess(cmd=[sys.executable, '-c', 'print("working")'], name='worker',
                            output='screen')
    return LaunchDescription([
        worker,
        RegisterEventHandler(OnProcessExit(target_action=worker, on_exit=[
            LogInfo(msg='worker exited')])),
        RegisterEventHandler(OnShutdown(on_shutdown=[
            LogInfo(msg=['shutdown because: ', LocalSubstitution('event.reason')]),
            OpaqueFunction(function=lambda context: print('cleanup ran', flush=True)),
        ])),
        RegisterEventHandler(OnShutdown(on_shutdown=lambda event, context: print(
            'second handler: reason=%s due_to_sigint=%s' % (event.reason, event.due_to_sigint),
            flush=True))),
    ])
"""

# `ros2 launch idle.launch.py` (reference run 2026-11-29), after "Default logging verbosity is
# set to INFO"; exit status 0
IDLE_EXPECTED = [
    "[INFO] [worker-1]: process started with pid [N]",
    "[worker-1] working",
    "[INFO] [worker-1]: process has finished cleanly [pid N]",
    "[INFO] [launch.user]: worker exited",
    "second handler: reason=idle due_to_sigint=False",
    "[INFO] [launch.user]: shutdown because: idle",
    "cleanup ran",
]


def test_on_shutdown_handlers_run_when_everything_has_exited(launch_dir: Path) -> None:
    (launch_dir / "idle.launch.py").write_text(IDLE)
    ran = run_launch(launch_dir, "idle.launch.py")
    assert ran.status == 0, ran.text
    assert ran.launch_lines() == IDLE_EXPECTED


ON_EXIT = """\
import sys
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, LogInfo


def report(event, context):
    print('on_exit called: %s returncode=%d name=%s config=%s' % (
        type(event).__name__, event.returncode, event.process_name,
        context.launch_configurations.get('who', '-')), flush=True)
    return [LogInfo(msg='returned by the function')]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('who', default_value='nobody'),
        ExecuteProcess(cmd=[sys.executable, '-c', 'import sys; sys.exit(3)'], name='failing',
                       on_exit=report),
        ExecuteProcess(cmd=[sys.executable, '-c', 'print("second")'], name='second',
                       output='screen', on_exit=[LogInfo(msg='second is done')]),
    ])
"""


def test_execute_process_takes_a_function_for_on_exit(launch_dir: Path) -> None:
    # `ros2 launch onexit.launch.py who:=me` (reference run 2026-11-29): after the failing
    # process's "process has died" line, "on_exit called: ProcessExited returncode=3
    # name=failing-1 config=me" then "[INFO] [launch.user]: returned by the function"; after
    # the second's "process has finished cleanly", "second is done"; exit status 0
    (launch_dir / "onexit.launch.py").write_text(ON_EXIT)
    ran = run_launch(launch_dir, "onexit.launch.py", "who:=me")
    assert ran.status == 0, ran.text
    lines = ran.launch_lines()
    died = next(
        i for i, line in enumerate(lines) if "[ERROR] [failing-1]: process has died" in line
    )
    assert lines[died + 1 : died + 3] == [
        "on_exit called: ProcessExited returncode=3 name=failing-1 config=me",
        "[INFO] [launch.user]: returned by the function",
    ]
    done = lines.index("[INFO] [second-2]: process has finished cleanly [pid N]")
    assert lines[done + 1] == "[INFO] [launch.user]: second is done"
