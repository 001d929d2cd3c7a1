"""The launcher's node host (launchkit/runtime/node_host.py, launchkit/stock/_node_host.py):
the stock nodes of a launch are forked from one pre-imported process instead of starting cold,
and stay processes of the launch (their trampoline is what the launcher supervises); a SIGKILLed
launcher leaves nothing behind; a dead host means cold starts, said once."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

from launchkit.runtime.fork_host import TRAMPOLINE
from launchkit.testing._deadline import Deadline, scaled
from tests.engine.launcher import Launcher, alive, wait_gone

ROOT = Path(__file__).parents[2]
URDF = ROOT / "urdf" / "three_wheeled_robot.urdf"
READY = "publishing robot 'three_wheeled_robot'"  # robot_state_publisher's first line
HOST = "launchkit.stock._node_host"


def _rsp(respawn: bool = False) -> str:
    flags = ' respawn="true" respawn_delay="0"' if respawn else ""
    return (
        '<node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp" '
        f'output="screen"{flags}>'
        f'<param name="robot_description" value="$(command \'cat {URDF}\')"/></node>'
    )


def _stat(pid: int) -> tuple[int, int]:
    """(parent pid, session id) of ``pid``."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return int(fields[1]), int(fields[3])


def _cmdline(pid: int) -> list[str]:
    return Path(f"/proc/{pid}/cmdline").read_text().split("\0")[:-1]


def _processes() -> list[int]:
    return [int(entry) for entry in os.listdir("/proc") if entry.isdigit()]


def _host_of(launcher: int) -> list[int]:
    """The launcher's node host and everything forked from it (they share its command line)."""
    found = []
    for pid in _processes():
        try:
            argv = _cmdline(pid)
        except OSError:
            continue
        if HOST in argv and argv[argv.index(HOST) + 2] == str(launcher) and alive(pid):
            found.append(pid)
    return found


def _node_of(trampoline: int, launcher: int) -> int:
    """The forked node that writes to the trampoline's stdout."""
    deadline = Deadline(30)
    target = os.readlink(f"/proc/{trampoline}/fd/1")
    while not deadline.expired():
        for pid in _host_of(launcher):
            try:
                if _stat(pid)[0] != launcher and os.readlink(f"/proc/{pid}/fd/1") == target:
                    return pid
            except OSError:
                continue
        time.sleep(0.05)
    raise AssertionError(f"no process forked from the node host writes to {trampoline}'s stdout")


def test_a_stock_node_is_forked_from_the_launchers_node_host(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(_rsp())
    launcher.wait_line(READY)
    trampoline = launcher.pids["robot_state_publisher-1"]
    assert any(arg.endswith("fork_trampoline.py") for arg in _cmdline(trampoline))
    [host] = [p for p in _host_of(launcher.proc.pid) if _stat(p)[0] == launcher.proc.pid]
    assert _stat(host)[1] == host  # a session of its own, watched by the orphan guard
    assert len(os.listdir(f"/proc/{host}/task")) == 1  # no thread: safe to fork
    node = _node_of(trampoline, launcher.proc.pid)
    # The node is the host's child, never exec'ed, in a session of its own, in the launch's
    # folder, with the trampoline's output streams.
    assert _stat(node) == (host, node)
    assert os.readlink(f"/proc/{node}/cwd") == str(tmp_path)
    for fd in (1, 2):
        assert os.readlink(f"/proc/{node}/fd/{fd}") == os.readlink(f"/proc/{trampoline}/fd/{fd}")
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    assert "robot_state_publisher-1]: process has finished cleanly" in launcher.text
    wait_gone([trampoline, node, host])


def test_an_empty_launch_starts_no_node_host(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run('<executable name="sleeper" cmd="sleep 300"/>')
    launcher.wait_line("process started with pid")
    assert _host_of(launcher.proc.pid) == []
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0


def test_sigkill_of_the_launcher_leaves_no_host_and_no_node(run) -> None:  # type: ignore[no-untyped-def]
    # Killed at once (the host importing), once the node is started (the host forking it),
    # and once it runs.
    for wait_for in (None, "robot_state_publisher-1]: process started", READY):
        launcher = run(_rsp())
        seen: set[int] = set()
        if wait_for is not None:
            launcher.wait_line(wait_for)
        deadline = Deadline(2)
        while not seen and not deadline.expired() and wait_for is not None:
            seen.update(_host_of(launcher.proc.pid))
            time.sleep(0.01)
        seen.update(_host_of(launcher.proc.pid))
        os.kill(launcher.proc.pid, signal.SIGKILL)
        launcher.proc.wait(scaled(10))
        seen.update(_host_of(launcher.proc.pid))
        wait_gone([*seen, *launcher.pids.values()], scaled(15))
        assert _host_of(launcher.proc.pid) == []


def test_a_dead_host_means_cold_starts_said_once(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(_rsp(respawn=True))
    launcher.wait_line(READY)
    [host] = [p for p in _host_of(launcher.proc.pid) if _stat(p)[0] == launcher.proc.pid]
    node = _node_of(launcher.pids["robot_state_publisher-1"], launcher.proc.pid)
    os.kill(host, signal.SIGKILL)
    # The running node goes on; when it ends its trampoline cannot know how, and says so.
    os.kill(node, signal.SIGKILL)
    launcher.wait_line("fork host gone")
    launcher.wait_line(READY, timeout=scaled(60), count=2)
    launcher.wait_line("node host exited")
    cold = launcher.pids["robot_state_publisher-1"]
    assert _cmdline(cold)[1:3] == ["-m", "launchkit.stock.robot_state_publisher.node"]
    os.kill(cold, signal.SIGKILL)  # and again: still cold, not said twice
    launcher.wait_line(READY, timeout=scaled(60), count=3)
    assert _cmdline(launcher.pids["robot_state_publisher-1"])[1:3] == [
        "-m",
        "launchkit.stock.robot_state_publisher.node",
    ]
    assert launcher.text.count("node host exited") == 1
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    wait_gone(list(launcher.pids.values()))


def test_no_host_where_none_can_be_made_and_the_nodes_start_cold(tmp_path: Path) -> None:
    # A temporary folder too deep for a Unix socket's path: no host, one line, cold nodes.
    deep = tmp_path / ("d" * 60) / ("e" * 60)
    deep.mkdir(parents=True)
    launch_file = tmp_path / "t.launch.xml"
    launch_file.write_text(f"<launch>{_rsp()}</launch>")
    launcher = Launcher(str(launch_file), cwd=tmp_path, env={"TMPDIR": str(deep)})
    try:
        launcher.wait_line(READY, timeout=scaled(60))
        assert launcher.text.count("no node host (") == 1
        pid = launcher.pids["robot_state_publisher-1"]
        assert _cmdline(pid)[1:3] == ["-m", "launchkit.stock.robot_state_publisher.node"]
        launcher.signal(signal.SIGINT)
        assert launcher.finish() == 0
        wait_gone([pid])
    finally:
        if launcher.proc.poll() is None:
            launcher.kill()


def _start_host(folder: Path) -> tuple[subprocess.Popen[bytes], str]:
    """A node host serving a socket in ``folder``, as the launcher starts one."""
    path = str(folder / "host.sock")
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    listener.bind(path)
    listener.listen(8)
    fd = listener.fileno()
    host = subprocess.Popen(
        [sys.executable, "-m", HOST, str(fd), str(os.getpid())],
        pass_fds=(fd,),
        start_new_session=True,
        env={**os.environ, "PYTHONPATH": str(ROOT), "OPENBLAS_NUM_THREADS": "1"},
        cwd=ROOT,
    )
    listener.close()
    return host, path


def test_a_forked_node_gets_its_argv_env_cwd_streams_and_status(tmp_path: Path) -> None:
    host, path = _start_host(tmp_path)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PROBE_VAR": "from the launch"}
    command = [sys.executable, "-I", "-S", TRAMPOLINE, path, sys.executable, "-m"]
    probe = [*command, "tests.engine.node_host_probe"]
    workdir = tmp_path / "work"
    workdir.mkdir()

    def run(args: list[str], stdin: str, **more_env: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*probe, *args],
            input=stdin,
            capture_output=True,
            text=True,
            cwd=workdir,
            env={**env, **more_env},
            timeout=scaled(60),
            check=False,
        )

    try:
        done = run(["3", "two words"], "hello\n")
        assert done.returncode == 3, done
        assert f"argv=['3', 'two words'] cwd={workdir} env=from the launch" in done.stdout
        assert "stdin=hello preloaded=True" in done.stdout
        assert done.stderr == "probe on stderr\n"
        # A signal to the trampoline reaches the node; the trampoline ends the same way.
        waiting = subprocess.Popen(
            [*probe, "wait"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, cwd=workdir, env=env
        )
        assert waiting.stdin is not None and waiting.stdout is not None
        waiting.stdin.write(b"\n")
        waiting.stdin.close()
        node = int(waiting.stdout.readline().split(b"pid=")[1])
        assert _stat(node)[0] == host.pid
        waiting.send_signal(signal.SIGTERM)
        assert waiting.wait(scaled(30)) == -signal.SIGTERM
        waiting.stdout.close()
        wait_gone([node])
        # Other interpreter settings: no fork, the command runs cold.
        other = run(["0"], "x\n", PYTHONHASHSEED="4321")
        assert other.returncode == 0 and "preloaded=False" in other.stdout, other
    finally:
        host.kill()
        host.wait()
    # No host: the trampoline runs the command itself.
    cold = run(["0"], "x\n")
    assert cold.returncode == 0 and "preloaded=False" in cold.stdout, cold
