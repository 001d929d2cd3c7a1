"""The run's log folder and files are bounded (issue #17, points 6 and 7): files rotate at a size,
a run stops logging child output at its cap, old runs are pruned (never ROS's folders, never a
running launch's), and a run that fails before starting still has its folder and error."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from launchkit.errors import UserError
from launchkit.runtime.logdir import RUN_MARKER, LogLimits, create_run_dir
from launchkit.runtime.logfiles import RunLogs
from tests.engine.launcher import run_launchkit


def test_a_log_file_rotates_at_its_size_and_keeps_the_latest(tmp_path: Path) -> None:
    logs = RunLogs(tmp_path, LogLimits(file_bytes=10_000, run_bytes=0))
    for index in range(5000):
        logs.write("talker-1-stdout.log", [f"line {index:05d}"], child=True)
    logs.close()
    current, previous = tmp_path / "talker-1-stdout.log", tmp_path / "talker-1-stdout.log.1"
    assert current.stat().st_size <= 10_000 and previous.stat().st_size <= 10_000
    assert current.read_text().splitlines()[-1] == "line 04999"
    assert sorted(p.name for p in tmp_path.iterdir()) == [current.name, previous.name]


def test_a_run_stops_logging_child_output_at_its_cap(tmp_path: Path) -> None:
    logs = RunLogs(tmp_path, LogLimits(file_bytes=0, run_bytes=50_000))
    for index in range(10_000):
        logs.write("launch.log", [f"[yes-1] y {index}"], child=True)
    logs.write("launch.log", ["[INFO] [launch]: the launcher's own lines still go in"], child=False)
    logs.close()
    text = (tmp_path / "launch.log").read_text()
    assert len(text) < 52_000
    assert "child output is no longer logged" in text
    assert text.rstrip().endswith("the launcher's own lines still go in")


def test_old_runs_are_pruned_but_not_ros_folders_nor_running_launches(tmp_path: Path) -> None:
    environment = {"ROS_LOG_DIR": str(tmp_path)}
    ros_own = tmp_path / "2000-01-01-00-00-00-000000-ros-1"  # ROS's own run: no marker
    ros_own.mkdir()
    running = create_run_dir(environment, keep_runs=2)  # the oldest, still held
    finished = []
    for _ in range(4):
        run = create_run_dir(environment, keep_runs=2)
        run.release()
        finished.append(run.path)
    names = {p.name for p in tmp_path.iterdir()}
    assert ros_own.name in names and running.path.name in names
    assert {finished[-2].name, finished[-1].name} <= names
    assert not (finished[0].exists() or finished[1].exists())
    assert (tmp_path / "latest").resolve() == finished[-1]
    running.release()


def test_log_limits_come_from_the_environment() -> None:
    limits = LogLimits.from_environment(
        {
            "LAUNCHKIT_LOG_FILE_MB": "0.5",
            "LAUNCHKIT_LOG_RUN_MB": "0",
            "LAUNCHKIT_LOG_KEEP_RUNS": "3",
        }
    )
    assert limits == LogLimits(file_bytes=512 * 1024, run_bytes=0, keep_runs=3)
    with pytest.raises(UserError, match="LAUNCHKIT_LOG_KEEP_RUNS='many'"):
        LogLimits.from_environment({"LAUNCHKIT_LOG_KEEP_RUNS": "many"})


def test_a_run_rejected_before_starting_has_its_log_folder(tmp_path: Path) -> None:
    path = tmp_path / "bad.launch.xml"
    path.write_text("<launch>\n  <nod/>\n</launch>\n")
    result = run_launchkit("run", str(path), cwd=tmp_path, env={"ROS_LOG_DIR": str(tmp_path)})
    assert result.returncode == 2
    latest = tmp_path / "latest"
    assert (latest / RUN_MARKER).exists(), "as ros2 launch: a run folder even for a bad file"
    log = (latest / "launch.log").read_text()
    assert f"{path}:2:" in log and "unknown tag <nod>" in log
    error, hint = result.stderr.splitlines()
    assert "unknown tag <nod>" in error and hint == "  hint: did you mean 'node'?"
    assert os.readlink(latest) == latest.resolve().name
