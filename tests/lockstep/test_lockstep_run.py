"""``launchkit run --lockstep``: timers and messages follow the launch's simulated clock, the
time advances only when every node is done, ``--until`` ends the launch with status 0, and a
scripted scenario of the seed robot prints the same floats in every run."""

from __future__ import annotations

import itertools
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from launchkit.testing._isolation import free_loopback_port

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

HERE = Path(__file__).parent / "launch"


def run_lockstep(launch_file: str, until: float, tmp_path: Path, *extra: str) -> str:
    """``launchkit run FILE --lockstep --until S``; its output (asserting status 0)."""
    env = {**os.environ, "PYTHON": sys.executable, "ROS_LOG_DIR": str(tmp_path / "log")}
    router = f"tcp/127.0.0.1:{free_loopback_port()}"
    command = [sys.executable, "-m", "launchkit", "run", "--router", router]
    command += [str(HERE / launch_file), "--lockstep", "--until", str(until), *extra]
    done = subprocess.run(
        command, env=env, capture_output=True, text=True, timeout=180, start_new_session=True
    )
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def assert_ticks_every_quarter_second(out: str) -> None:
    """A tick every 0.25 s of simulated time, each heard at the instant it was sent."""
    ticks = re.findall(r"tick (\d+) at (\d+)", out)
    heard = re.findall(r"heard (\d+) at (\d+)", out)
    assert ticks == [(str(n), str(n * 250_000_000)) for n in range(1, 9)]
    assert heard == ticks


def test_timers_and_messages_follow_the_simulated_clock(tmp_path: Path) -> None:
    out = run_lockstep("ticker.launch.xml", 2.0, tmp_path)
    assert_ticks_every_quarter_second(out)
    assert re.search(r"reached the simulated time 2.000 s in \d+ steps \(--until\)", out)


def test_a_rate_loop_stops_the_clock_at_each_wake_up(tmp_path: Path) -> None:
    # The loop's period starts when its thread first sleeps: until then its work is outside
    # callbacks, unseen by the lockstep (docs/simulation.md), and the time may have moved a
    # step. From there, every wake-up is exactly one period apart and heard at its instant.
    out = run_lockstep("rate.launch.xml", 2.0, tmp_path)
    ticks = re.findall(r"tick (\d+) at (\d+)", out)
    assert [int(count) for count, _ in ticks] == list(range(1, len(ticks) + 1))
    times = [int(at) for _, at in ticks]
    assert len(times) >= 7 and 250_000_000 <= times[0] <= 500_000_000, ticks
    periods = {later - earlier for earlier, later in itertools.pairwise(times)}
    assert periods == {250_000_000}, ticks
    assert re.findall(r"heard (\d+) at (\d+)", out) == ticks


def test_rtf_caps_the_pace(tmp_path: Path) -> None:
    """At --rtf 2 the 1.75 simulated seconds from the first tick to the last take at least
    0.875 s of wall time (unpaced they take a small fraction of that)."""
    env = {**os.environ, "PYTHON": sys.executable, "ROS_LOG_DIR": str(tmp_path / "log")}
    command = [sys.executable, "-m", "launchkit", "run", "--router"]
    command += [f"tcp/127.0.0.1:{free_loopback_port()}", str(HERE / "ticker.launch.xml")]
    command += ["--lockstep", "--rtf", "2", "--until", "2"]
    seen: dict[str, float] = {}
    with subprocess.Popen(command, env=env, stdout=subprocess.PIPE, text=True) as launch:
        assert launch.stdout is not None
        for line in launch.stdout:
            for tick in ("tick 1 at", "tick 8 at"):
                if tick in line:
                    seen[tick] = time.monotonic()
        assert launch.wait(timeout=60) == 0
    assert seen["tick 8 at"] - seen["tick 1 at"] >= 0.875 * 0.95


def test_until_needs_lockstep(tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "run", str(HERE / "ticker.launch.xml"), "--until", "1"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2
    assert "error: --until needs --lockstep" in done.stderr


def test_the_seed_scenario_prints_the_same_floats_every_run(tmp_path: Path) -> None:
    answers = set()
    for run in range(3):
        out = run_lockstep("scenario.launch.xml", 3.5, tmp_path / str(run))
        (line,) = [line for line in out.splitlines() if "ODOM at" in line]
        answers.add(line.split("ODOM at", 1)[1])
    assert len(answers) == 1, answers
