"""Signals are honoured at every moment, whatever the launch file and the children do (issue
#17, point 2): while a ``$(command)`` runs, while children flood their output, and output
without newlines costs linear time in bounded memory.

Every assertion is on an outcome with a generous deadline (exit status before D seconds, RSS
under N MB, no survivor), never on how fast something went.
"""

from __future__ import annotations

import os
import signal
import socket
import time
from pathlib import Path

import pytest

from launchkit.runtime.child_requests import MAX_REFUSED
from launchkit.runtime.lines import MAX_LINE_BYTES, SPLIT_MARK, LineBuffer
from tests.conftest import EvaluateXml
from tests.engine.conftest import write
from tests.engine.launcher import Launcher, alive, executable, wait_gone


def _wait_for_file(path: Path, timeout: float = 30.0) -> str:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if path.exists() and path.read_text().strip():
            return path.read_text().strip()
        time.sleep(0.05)
    raise AssertionError(f"{path} was not written within {timeout} s")


def _rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return 0.0


@pytest.mark.parametrize(
    ("signum", "status"), [(signal.SIGINT, 0), (signal.SIGTERM, 128 + signal.SIGTERM)]
)
def test_a_signal_during_command_substitution_stops_it_and_its_group(
    run, tmp_path: Path, signum: int, status: int
) -> None:  # type: ignore[no-untyped-def]
    marker = tmp_path / "grandchild"
    command = f"sh -c &quot;sleep 300 &amp; echo $! &gt; {marker}; wait&quot;"
    launcher = run(
        f"<log message=\"$(command '{command}')\"/>\n"
        '<executable name="never" cmd="touch never-started"/>'
    )
    grandchild = int(_wait_for_file(marker))
    launcher.signal(signum)
    # it used to wait for the command to end (300 s here) before noticing
    assert launcher.finish(timeout=20) == status
    wait_gone([grandchild])
    assert not (tmp_path / "never-started").exists()
    assert "Traceback" not in launcher.text


def test_sigterm_during_print_kills_the_command_it_waits_for(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    marker = tmp_path / "grandchild"
    command = f"sh -c &quot;sleep 300 &amp; echo $! &gt; {marker}; wait&quot;"
    launcher = run(f"<log message=\"$(command '{command}')\"/>", "--print")
    grandchild = int(_wait_for_file(marker))
    launcher.signal(signal.SIGTERM)  # its default action would leave the command running
    assert launcher.finish(timeout=20) == 128 + signal.SIGTERM
    wait_gone([grandchild])


def test_a_signal_during_a_timer_command_stops_the_launch(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    marker = tmp_path / "command"
    command = f"sh -c &quot;echo $$ &gt; {marker}; exec sleep 300&quot;"
    launcher = run(
        executable("py", "import time; print('ready', flush=True); time.sleep(300)")
        + f'\n<timer period="0.1"><log message="$(command \'{command}\')"/></timer>'
    )
    # the timer's $(command) holds the launcher's loop, as in ROS 2 launch: on a busy machine it
    # may start before py's "ready" is read, so wait for py's start line and the command instead
    launcher.wait_line("[py-1]: process started with pid")
    command_pid = int(_wait_for_file(marker))
    launcher.signal(signal.SIGINT)
    assert launcher.finish(timeout=30) == 0
    wait_gone([command_pid, *launcher.pids.values()])


FLOODERS = (
    '<executable name="yes" cmd="yes"/>\n'
    '<executable name="zeros" cmd="sh -c \'head -c 200M /dev/zero; sleep 300\'"/>\n'
    '<executable name="lines" output="screen" cmd="sh -c \'while :; do echo tick; done\'"/>'
)


def test_floods_neither_starve_signals_nor_grow_the_launcher(tmp_path: Path) -> None:
    path = write(tmp_path, FLOODERS)
    launcher = Launcher(
        str(path),
        cwd=tmp_path,
        env={"ROS_LOG_DIR": str(tmp_path), "LAUNCHKIT_LOG_FILE_MB": "20"},
    )
    try:
        launcher.wait_line("[lines-3] tick")
        flooders = list(launcher.pids.values())
        peak = 0.0
        deadline = time.monotonic() + 2
        while time.monotonic() < deadline:  # let the floods run a while, watching memory
            peak = max(peak, _rss_mb(launcher.proc.pid))
            time.sleep(0.1)
        launcher.signal(signal.SIGTERM)
        status = launcher.finish(timeout=30)
    finally:
        if launcher.proc.poll() is None:
            launcher.kill()
    assert status == 128 + signal.SIGTERM
    wait_gone(flooders)
    # it used to grow by the size of the floods (800 MB and more)
    assert peak < 200, f"the launcher's RSS reached {peak:.0f} MB under the floods"
    logs = [p for p in (tmp_path / "latest").iterdir() if p.suffix in (".log", ".1")]
    assert all(p.stat().st_size <= 21 * 1024 * 1024 for p in logs), "a log file passed its cap"


def test_long_lines_are_split_and_marked(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        executable(
            "long",
            "import sys; sys.stdout.write('a' * 150000 + 'end' + chr(10)); sys.stdout.flush()",
        )
    )
    assert launcher.finish() == 0
    pieces = [line for line in launcher.lines if line.startswith("[long-1] a")]
    assert len(pieces) == 3, launcher.text[:500]
    assert all(p.endswith(SPLIT_MARK) for p in pieces[:2]) and pieces[2].endswith("aend")
    text = "".join(p.removeprefix("[long-1] ").removesuffix(SPLIT_MARK) for p in pieces)
    assert text == "a" * 150000 + "end"


def test_line_buffer_is_bounded_and_keeps_every_byte() -> None:
    buffer = LineBuffer()
    out: list[str] = []
    data = ("é" * 100_000 + "\n" + "x" * 10 + "\n" + "z" * 300_000).encode()
    for start in range(0, len(data), 7_777):  # reads of any size
        out += buffer.feed(data[start : start + 7_777])
        assert buffer.pending <= MAX_LINE_BYTES
    out += buffer.finish()
    assert all(len(line.removesuffix(SPLIT_MARK).encode()) <= MAX_LINE_BYTES for line in out)
    assert "\ufffd" not in "".join(out), "a piece was cut inside a UTF-8 character"
    joined = "".join(
        line.removesuffix(SPLIT_MARK) + ("" if line.endswith(SPLIT_MARK) else "\n") for line in out
    )
    assert joined == data.decode() + "\n"


def test_refused_child_request_connections_are_closed(run) -> None:  # type: ignore[no-untyped-def]
    code = (
        "import os, time; print('socket', os.environ['LAUNCHKIT_SUPERVISOR_SOCKET'], flush=True); "
        "time.sleep(300)"
    )
    launcher = run(executable("owner", code))
    path = launcher.wait_line("[owner-1] socket ").split()[-1]
    launcher_pid = launcher.proc.pid
    baseline = len(os.listdir(f"/proc/{launcher_pid}/fd"))
    outsiders: list[socket.socket] = []
    try:
        # This test process is no process of the launch: every connection is refused. It keeps
        # them all open, as a hostile loop would; half of them never even send a request.
        for index in range(300):
            outsider = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
            outsiders.append(outsider)
            outsider.settimeout(30)
            outsider.connect(path)
            if index % 2:
                outsider.send(b'{"op": "announce", "text": "hi"}')
                assert b"is not a process of this launch" in outsider.recv(65536)
        with socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET) as last:
            last.settimeout(30)
            last.connect(path)  # answered: every earlier connection has been seen by now
            last.send(b'{"op": "announce", "text": "hi"}')
            assert b"is not a process of this launch" in last.recv(65536)
        held = len(os.listdir(f"/proc/{launcher_pid}/fd")) - baseline
    finally:
        for outsider in outsiders:
            outsider.close()
    assert held <= MAX_REFUSED + 4, f"the launcher holds {held} more descriptors"
    assert alive(launcher_pid)
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0


def test_what_a_command_substitution_leaves_running_is_killed(evaluate_xml: EvaluateXml) -> None:
    command = "sh -c &quot;sleep 300 &gt;/dev/null 2&gt;&amp;1 &amp; echo $!&quot;"
    result = evaluate_xml(f"<launch><log message=\"$(command '{command}')\"/></launch>")
    leftover = int(result.messages()[0])
    wait_gone([leftover])  # ROS leaves it running, past the end of the launch
