"""A process that cannot start because its working folder is missing fails alone, as in Jazzy:
one error line for it, and the rest of the launch runs.

Expectation from the real launch (``ros2_launch.py`` of the reference tools: launch 3.4.3,
launch_ros 0.26.6) on the same file.
"""

from __future__ import annotations

from pathlib import Path

from tests.compat.conftest import run_launch

CWD = """\
import sys
from launch import LaunchDescription
from launch.actions import ExecuteProcess, LogInfo, TimerAction


def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=[sys.executable, '-c', 'print("in the missing folder")'],
                       name='lost', cwd='{missing}', output='screen'),
        ExecuteProcess(cmd=[sys.executable, '-c',
                            'import time; print("fine"); time.sleep(1); print("still fine")'],
                       name='fine', output='screen'),
        TimerAction(period=0.5, actions=[LogInfo(msg='timer fired')]),
    ])
"""


def test_a_missing_working_folder_fails_only_its_process(launch_dir: Path) -> None:
    # `ros2 launch cwd.launch.py` (reference run 2026-11-29): "[ERROR] [lost-1]: exception
    # occurred while executing process:" and a traceback ending "FileNotFoundError: [Errno 2]
    # No such file or directory: '<the folder>'"; then fine-2 starts, prints "fine", the timer
    # fires, "still fine", fine-2 finishes cleanly; exit status 0. launchkit says it in one line.
    missing = launch_dir / "no" / "such" / "folder"
    path = launch_dir / "cwd.launch.py"
    path.write_text(CWD.format(missing=missing))
    ran = run_launch(launch_dir, "cwd.launch.py")
    assert ran.status == 0, ran.text
    lines = ran.launch_lines()
    # the timer counts wall time from the launch's start: on a busy machine it may fire before
    # the process's Python has printed its first line, so only its presence is compared
    assert "[INFO] [launch.user]: timer fired" in lines
    assert [line for line in lines if "timer fired" not in line] == [
        f"[ERROR] [lost-1]: could not start process: its working folder '{missing}' does not "
        f"exist ({path}:8)",
        "[INFO] [fine-2]: process started with pid [N]",
        "[fine-2] fine",
        "[fine-2] still fine",
        "[INFO] [fine-2]: process has finished cleanly [pid N]",
    ]
    assert "Traceback" not in ran.text
