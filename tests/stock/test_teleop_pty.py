"""teleop_twist_keyboard in a real pseudo-terminal, with a subscriber checking /cmd_vel."""

from __future__ import annotations

import os
import shlex
import signal
import sys
from pathlib import Path
from typing import Any

import pexpect
import pytest
from launchkit.ros.msgs.geometry_msgs.msg import Twist, TwistStamped

from tests.stock.conftest import spin_until

MODULE = "launchkit.stock.teleop_twist_keyboard.node"


def _spawn(*ros_args: str) -> Any:
    """The node in a pty; ``stty -a`` runs after it exits to show the terminal it left behind."""
    node = shlex.join([sys.executable, "-m", MODULE, *ros_args])
    return pexpect.spawn(
        "/bin/sh", ["-c", f"{node}; echo EXIT=$?; stty -a"], encoding="utf-8", timeout=20
    )


def _close(child: Any) -> None:
    if child.isalive():
        child.terminate(force=True)
    child.close()


def test_keys_publish_twists_and_ctrl_c_restores_the_terminal(router: str, probe: Any) -> None:
    received: list[Any] = []
    probe.create_subscription(Twist, "/cmd_vel", received.append, 10)
    child = _spawn()
    try:
        child.expect_exact("Moving around:")
        child.expect_exact("currently:\tspeed 0.50\tturn 1.00 ")
        spin_until(
            probe,
            lambda: probe.count_publishers("/cmd_vel") > 0,
            "teleop's /cmd_vel publisher in the graph",
        )

        child.send("i")
        spin_until(probe, lambda: any(m.linear.x == 0.5 for m in received), "forward twist")
        child.send("q")
        child.expect_exact("currently:\tspeed 0.55\tturn 1.10 ")
        spin_until(
            probe,
            lambda: received[-1].linear.x == pytest.approx(0.55),
            "forward twist at the new speed",
        )
        child.send("J")
        spin_until(probe, lambda: received[-1].linear.y == pytest.approx(0.55), "strafe left")
        child.send("k")
        spin_until(probe, lambda: received[-1].linear.y == 0.0, "stop on k")
        child.send("\x03")
        child.expect_exact("EXIT=0")
        spin_until(probe, lambda: received[-1] == Twist(), "the zero twist sent on exit")
        child.expect(r"\r\n.*\bicanon\b")  # cooked mode again: raw mode would show -icanon
        stty = child.before + child.after + child.read()
        assert " -icanon" not in stty and " -echo " not in stty, stty
    finally:
        _close(child)


def test_stamped_publishes_twist_stamped_with_the_frame(router: str, probe: Any) -> None:
    received: list[Any] = []
    probe.create_subscription(TwistStamped, "/cmd_vel", received.append, 10)
    child = _spawn("--ros-args", "-p", "stamped:=true", "-p", "frame_id:=base")
    try:
        child.expect_exact("CTRL-C to quit")
        spin_until(probe, lambda: probe.count_publishers("/cmd_vel") > 0, "teleop's publisher")
        child.send("j")
        spin_until(probe, lambda: bool(received), "a TwistStamped")
        assert received[0].header.frame_id == "base"
        assert received[0].twist.angular.z == 1.0
        child.send("\x03")
        child.expect_exact("EXIT=0")
    finally:
        _close(child)


def test_frame_id_without_stamped_is_a_user_error(router: str) -> None:
    child = _spawn("--ros-args", "-p", "frame_id:=base")
    try:
        child.expect_exact("EXIT=2")
        assert "frame_id only together with stamped:=true" in child.before
        assert "Traceback" not in child.before
    finally:
        _close(child)


def test_not_a_terminal_is_a_user_error(router: str) -> None:
    import subprocess

    proc = subprocess.run(
        [sys.executable, "-m", MODULE],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert proc.returncode == 2
    assert "is not one" in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_signals_stop_the_robot_and_restore_the_terminal(
    router: str, probe: Any, signum: int
) -> None:
    received: list[Any] = []
    probe.create_subscription(Twist, "/cmd_vel", received.append, 10)
    child = _spawn()
    try:
        child.expect_exact("CTRL-C to quit")
        spin_until(probe, lambda: probe.count_publishers("/cmd_vel") > 0, "teleop's publisher")
        child.send("i")
        spin_until(probe, lambda: bool(received) and received[-1].linear.x == 0.5, "forward")
        node_pid = _node_pid(child.pid)
        os.kill(node_pid, signum)
        child.expect_exact("EXIT=0")
        spin_until(probe, lambda: received[-1] == Twist(), f"the zero twist sent on {signum}")
        stty = child.read()
        assert " -icanon" not in stty and " -echo " not in stty, stty
    finally:
        _close(child)


def _node_pid(shell_pid: int) -> int:
    """The teleop process started by the test's shell (its only child)."""
    children = Path(f"/proc/{shell_pid}/task/{shell_pid}/children").read_text().split()
    assert len(children) == 1, children
    return int(children[0])
