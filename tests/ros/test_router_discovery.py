"""Discovery without an extra step: the shared background router, and commands that wait.

Each test has its own router port and runtime folder (``XDG_RUNTIME_DIR``), and stops the
shared router it caused, whatever happened.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_helpers import NODES_DIR, Child, demo_package, stderr_line

from launchkit.ros.router import start_router
from launchkit.ros.shared_router import SharedRouterState, stop_shared_router
from launchkit.testing._isolation import free_loopback_port, router_endpoint


@pytest.fixture
def shared(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """An endpoint where no router runs yet, with the shared router allowed to start there."""
    endpoint = router_endpoint(free_loopback_port())
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    monkeypatch.setenv("LAUNCHKIT_ROUTER_AUTOSTART", "1")
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(tmp_path))
    try:
        yield endpoint
    finally:
        stop_shared_router(endpoint)
    assert _router_processes(endpoint) == [], "a shared router outlived its test"


def _router_processes(endpoint: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                command = (entry / "cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if b"launchkit.ros.router_daemon" in command and endpoint.encode() in command:
                found.append(int(entry.name))
    return found


def launchkit(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit ARGS`` to completion (in the test's environment)."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args], capture_output=True, text=True, timeout=timeout
    )


def _stat_fields(pid: int) -> list[str]:
    return Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()


def test_two_execs_find_each_other_through_the_shared_router(
    shared: str, tmp_path: Path, children: list[Child]
) -> None:
    demo_package(tmp_path / "prefix")
    env = {"AMENT_PREFIX_PATH": str(tmp_path / "prefix")}
    listener = Child(["-m", "launchkit", "exec", "demo", "listener"], env=env)
    children.append(listener)
    talker = Child(["-m", "launchkit", "exec", "demo", "talker"], env=env)
    children.append(talker)
    listener.expect("heard: hello", timeout=30)

    state = SharedRouterState.read(shared)
    assert state is not None, "no shared router was started"
    assert _router_processes(shared) == [state.pid]
    # nobody's child, in a session of its own, no terminal, output to its log file
    ppid, sid, tty = (int(f) for f in (_stat_fields(state.pid)[1], *_stat_fields(state.pid)[3:5]))
    assert ppid not in (listener.proc.pid, talker.proc.pid, os.getpid())
    assert sid not in (os.getsid(listener.proc.pid), os.getsid(talker.proc.pid), os.getsid(0))
    assert tty == 0
    assert os.readlink(f"/proc/{state.pid}/fd/0") == os.devnull
    assert (
        os.readlink(f"/proc/{state.pid}/fd/1")
        == state.log
        == os.readlink(f"/proc/{state.pid}/fd/2")
    )
    assert os.readlink(f"/proc/{state.pid}/cwd") == "/"

    status = launchkit("router", "status")
    assert status.returncode == 0, status.stderr
    assert f"shared ROS router at {shared}: running (pid {state.pid}," in status.stdout
    assert "connection(s) now" in status.stdout

    stopped = launchkit("router", "stop")
    assert stopped.stdout == f"stopped the shared ROS router at {shared} (pid {state.pid})\n"
    assert _router_processes(shared) == []
    after = launchkit("router", "status")
    assert after.returncode == 1 and after.stdout == f"no ROS router answers at {shared}\n"


def test_processes_starting_at_once_end_with_one_router(shared: str) -> None:
    starters = [
        subprocess.Popen(
            [sys.executable, "-m", "launchkit", "router", "start"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(4)
    ]
    outputs = [starter.communicate(timeout=90) for starter in starters]
    assert [starter.returncode for starter in starters] == [0] * 4, outputs
    started = [out for out, _ in outputs if out.startswith("started the shared ROS router")]
    assert len(started) == 1, outputs
    assert len(_router_processes(shared)) == 1


def test_the_shared_router_exits_once_unused(
    shared: str, children: list[Child], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("LAUNCHKIT_ROUTER_IDLE_TIMEOUT", "1")
    listener = Child([str(NODES_DIR / "listener.py")])  # starts the shared router
    children.append(listener)
    listener.expect("listener ready", timeout=30)
    state = SharedRouterState.read(shared)
    assert state is not None and state.idle_timeout == 1.0
    # connected for several idle timeouts: the router stays
    connected_since = time.monotonic()
    while time.monotonic() - connected_since < 3.5:
        assert SharedRouterState.read(shared) is not None, "the router quit under a node"
        time.sleep(0.1)
    listener.stop()
    # it exits 1 s after the last one left (but not within 10 s of its start, its starter's
    # time to connect)
    deadline = time.monotonic() + 30
    while _router_processes(shared):
        assert time.monotonic() < deadline, "the unused shared router did not exit"
        time.sleep(0.1)
    assert "nothing connected for 1 s: exiting" in Path(state.log).read_text()
    assert not SharedRouterState.path(shared).exists()


def test_a_command_waits_for_the_router_saying_so_once(
    children: list[Child], monkeypatch: pytest.MonkeyPatch
) -> None:
    endpoint = router_endpoint(free_loopback_port())
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)  # autostart is off in the suite
    echo = Child(["-m", "launchkit", "topic", "echo", "/chatter", "--once"])
    children.append(echo)
    stderr_line(echo, f"Unable to connect to a ROS router at {endpoint}: waiting", timeout=30)
    router = start_router(endpoint)
    try:
        talker = Child([str(NODES_DIR / "talker.py")])
        children.append(talker)
        echo.expect("data: hello", timeout=30)
        assert echo.proc.wait(timeout=30) == 0
    finally:
        router.close()
    assert echo.stderr.count("Unable to connect") == 1


def talker_launch(folder: Path) -> Child:
    """``launchkit run`` of a launch file starting package ``demo``'s talker (made in
    ``folder``)."""
    demo_package(folder / "prefix")
    launch = folder / "talk.launch.xml"
    launch.write_text('<launch><node pkg="demo" exec="talker"/></launch>\n')
    env = {"AMENT_PREFIX_PATH": str(folder / "prefix")}
    return Child(["-m", "launchkit", "run", str(launch)], env=env)


def test_echo_right_after_run_prints_the_first_message(
    shared: str, tmp_path: Path, children: list[Child]
) -> None:
    # issue #9: `launchkit run robot.launch.xml &` then at once `launchkit topic echo ... --once`
    launcher = talker_launch(tmp_path)
    children.append(launcher)
    echo = Child(["-m", "launchkit", "topic", "echo", "/chatter", "--once"])
    children.append(echo)
    echo.expect("data: hello", timeout=60)
    assert echo.proc.wait(timeout=30) == 0, echo.stderr
    assert launcher.stop(timeout=15) == 0


def test_a_launch_joins_the_shared_router_a_command_started(
    shared: str, tmp_path: Path, children: list[Child]
) -> None:
    echo = Child(["-m", "launchkit", "topic", "echo", "/chatter", "--once"])
    children.append(echo)
    echo.expect("WARNING: topic [/chatter] does not appear to be published yet", timeout=60)
    assert SharedRouterState.read(shared) is not None
    launcher = talker_launch(tmp_path)
    children.append(launcher)
    launcher.expect(f"joined the shared ROS router at {shared}", timeout=60)
    echo.expect("data: hello", timeout=60)
    assert echo.proc.wait(timeout=30) == 0
    assert launcher.stop(timeout=15) == 0
    assert SharedRouterState.read(shared) is not None  # the launch leaves it to its idle timeout


def test_status_names_a_router_that_is_not_the_shared_one_and_stop_leaves_it(
    shared: str,
) -> None:
    router = start_router(shared)  # hosted by this test process, as a launch hosts one
    try:
        status = launchkit("router", "status")
        assert status.returncode == 0
        assert f"ROS router at {shared}: pid {os.getpid()} (" in status.stdout
        assert "not the shared background router" in status.stdout
        stopped = launchkit("router", "stop")
        assert stopped.returncode == 1
        assert "is not the shared background router" in stopped.stderr
        assert launchkit("router", "status").returncode == 0  # still there
    finally:
        router.close()
