"""The robot across two hosts, as a real one is used: the simulation, the state publisher and
the launcher on host A (the robot); the viewer (run by host B's agent), teleop and a recording
of /odom on host B (the laptop); routers linked by mutual TLS."""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path

import pexpect
from certs import Authority
from netns import Hosts, host_environment

PROBE = Path(__file__).resolve().parent / "nodes" / "viewer_probe.py"
SPEED = re.compile(r"twist:\n  twist:\n    linear:\n      x: (-?[0-9.e+-]+)")


def test_simulation_on_a_viewer_teleop_and_recording_on_b(hosts: Hosts, tmp_path: Path) -> None:
    ca = Authority("robot-ca")
    a_certs = ca.host_folder(tmp_path / "robot", "robot", hosts.a.address)
    b_certs = ca.host_folder(tmp_path / "laptop", "laptop", hosts.b.address)
    env = {"LAUNCHKIT_AGENT_KEY": str(tmp_path / "agent.key")}
    link = f"tls/{hosts.b.address}:7448"
    agent = hosts.b.launchkit(
        "agent", "--name", "laptop", "--listen", link, "--mtls", str(b_certs), env=env
    )
    agent.expect("agent laptop ready")
    robot = hosts.a.launchkit(
        "run", "robot_wheel", "gazebo_and_rviz.launch.xml", "viewer_machine:=laptop",
        "--connect", link, "--mtls", str(a_certs), env=env,
    )  # fmt: skip
    robot.expect(f"linked to the router at {link}", timeout=60)
    robot.expect("Successfully spawned entity", timeout=90)
    agent.expect("started rviz2-", timeout=90)

    # the viewer on B shows the robot described and moved on A
    probe = hosts.b.start(str(PROBE), "8765")
    probe.expect("page: 200", timeout=60)
    assert probe.expect("robot: ", timeout=90) == "robot: True"
    assert "base" in probe.expect("frames: ", timeout=30)

    # the recording on B sees teleop on B drive the robot on A
    recording = hosts.b.launchkit("topic", "echo", "/odom")
    recording.expect("twist:", timeout=90)
    teleop = pexpect.spawn(
        "ip",
        ["netns", "exec", hosts.b.name, sys.executable, "-m", "launchkit", "exec",
         "teleop_twist_keyboard", "teleop_twist_keyboard"],
        encoding="utf-8",
        timeout=60,
        env=host_environment(),
    )  # fmt: skip
    try:
        teleop.expect_exact("Moving around:")
        teleop.send("i")  # forward at 0.5 m/s
        _until_speed(recording, lambda x: abs(x) > 0.4)
        teleop.send("k")
        _until_speed(recording, lambda x: abs(x) < 0.02)
        teleop.sendcontrol("c")
        teleop.expect(pexpect.EOF)
    finally:
        teleop.close(force=True)
    assert teleop.exitstatus == 0

    assert robot.stop(timeout=60) == 0  # Ctrl-C on the launcher stops the viewer on B too
    assert not [line for line in robot.seen if "[ERROR]" in line], robot.seen[-30:]
    for pid in hosts.b.pids():
        command = Path(f"/proc/{pid}/cmdline").read_bytes()
        assert b"rviz2" not in command, command


def _until_speed(recording, check) -> None:  # type: ignore[no-untyped-def]
    """Read the recorded /odom messages until one's forward speed passes ``check``."""
    deadline = time.monotonic() + 60
    text = ""
    while time.monotonic() < deadline:
        line = recording.expect("", timeout=max(0.1, deadline - time.monotonic()))
        if line != "---":
            text += line + "\n"
            continue
        match = SPEED.search(text)
        if match and check(float(match.group(1))):
            return
        text = ""
    raise AssertionError("no recorded /odom message had the speed awaited within 60 s")
