"""Processes started at the request of a process of the launch, through the launcher's
child-request socket (launchkit/runtime/child_requests.py): real launchers, real processes.

The owner is a Python script that asks with ``SupervisorClient``; the launcher is driven
directly (tests/engine/launcher.py) where the test signals or SIGKILLs it, and through the
pytest plugin where the plugin's view of the launch is what is tested. No sleeps: every wait is
on a printed line, with a deadline.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from pathlib import Path

import pytest

from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError
from tests.engine.launcher import alive, executable, wait_gone

KID = "import time; print('kid up', flush=True); time.sleep(300)"
STUBBORN_KID = (
    "import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); "
    "signal.signal(signal.SIGTERM, signal.SIG_IGN); print('kid up', flush=True); time.sleep(300)"
)
OWNER = """\
import os, sys, time
from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError

KID = @KID@
client = SupervisorClient.from_environment()
kid = client.start("kid", [sys.executable, "-c", KID], respawn=True, respawn_delay=0.1)
print("owner asked for", kid.label, flush=True)
@THEN@
print("owner done", flush=True)
time.sleep(300)
"""
PRINT_SOCKET = 'print("socket", os.environ["LAUNCHKIT_SUPERVISOR_SOCKET"], flush=True)\n'
BAD_REQUESTS_THEN_STOP = (
    PRINT_SOCKET
    + """\
bad = [
    {"op": "reboot"},
    {"op": "start", "name": "x"},
    {"op": "start", "name": "x", "cmd": ["no-such-program-xyz"]},
    {"op": "start", "name": "x", "cmd": ["true"], "colour": "red"},
    {"op": "stop", "id": 99},
    {"op": "start", "name": "x", "cmd": ["a\\0b"]},
]
for request in bad:
    try:
        client.request(request)
    except SupervisorError as error:
        print("refused:", error, flush=True)
client._socket.send(b"not json")
print("refused:", client._socket.recv(65536).decode(), flush=True)
for stopped in (kid, client.start("once", [sys.executable, "-c", KID])):
    client.stop(stopped.id)
    while os.path.exists(f"/proc/{stopped.pid}"):  # until the launcher has reaped it
        time.sleep(0.01)
other = client.start("other", [sys.executable, "-c", KID])
print("owner asked for", other.label, flush=True)
"""
)


def owner(tmp_path: Path, kid: str = KID, then: str = "") -> str:
    """An ``<executable>`` running an owner script that asks for ``kid``, then runs ``then``."""
    script = tmp_path / "owner.py"
    script.write_text(OWNER.replace("@KID@", repr(kid)).replace("@THEN@", then))
    return f'<executable name="owner" output="screen" cmd="{sys.executable} {script}"/>'


def test_a_requested_child_is_prefixed_respawned_and_stopped_with_its_owner(run, tmp_path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(owner(tmp_path))
    launcher.wait_line("[kid-2] kid up")
    assert "[owner-1] owner asked for kid-2" in launcher.text
    assert "[owner-1] kid up" not in launcher.text
    first = launcher.pids["kid-2"]
    os.kill(first, signal.SIGKILL)
    launcher.wait_line("[kid-2] kid up", count=2)
    second = launcher.pids["kid-2"]
    assert second != first
    # The owner goes: its connection closes, the launcher stops the kid, then the launch ends.
    os.kill(launcher.pids["owner-1"], signal.SIGTERM)
    assert launcher.finish() == 0
    assert "owner-1 closed its child-request connection: stopping kid-2" in launcher.text
    assert launcher.text.count("[INFO] [kid-2]: process started with pid") == 2
    wait_gone([first, second, launcher.pids["owner-1"]])


def test_ctrl_c_stops_requested_children(run, tmp_path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(owner(tmp_path) + "\n" + executable("declared", KID))
    launcher.wait_line("[kid-3] kid up")  # the declared ones are numbered first
    launcher.wait_line("[declared-2] kid up")
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    assert "sending signal 'SIGINT' to process[kid-3]" in launcher.text
    wait_gone(list(launcher.pids.values()))


def test_launcher_killed_with_sigkill_leaves_no_requested_child(run, tmp_path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(owner(tmp_path, kid=STUBBORN_KID, then=PRINT_SOCKET))
    launcher.wait_line("[kid-2] kid up")
    folder = Path(launcher.wait_line("[owner-1] socket ").split()[-1]).parent
    pids = list(launcher.pids.values())
    assert len(pids) == 2 and all(alive(pid) for pid in pids)
    os.kill(launcher.proc.pid, signal.SIGKILL)
    launcher.proc.wait(10)
    wait_gone(pids)  # the orphan guard covers the requested child's process group too
    deadline = time.monotonic() + 10
    while folder.exists():  # ... and removes the socket's folder after the kills
        assert time.monotonic() < deadline, f"{folder} was left behind"
        time.sleep(0.02)


def test_bad_requests_are_refused_and_a_stop_request_stops_for_good(run, tmp_path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(owner(tmp_path, then=BAD_REQUESTS_THEN_STOP))
    launcher.wait_line("[owner-1] owner done")
    refusals = [line.split("refused: ", 1)[1] for line in launcher.lines if "refused: " in line]
    assert refusals[0] == "unknown op 'reboot' (expected 'start', 'stop' or 'announce')"
    assert refusals[1] == "cmd must be a non-empty list of strings (the argv)"
    assert refusals[2] == "program 'no-such-program-xyz' of process 'x' not found"
    assert refusals[3] == "unknown field(s) colour in a start request"
    assert refusals[4] == "no process 99 was started by this connection"
    assert refusals[5] == "cmd must not contain NUL characters"
    assert '"ok": false' in refusals[6] and "not JSON" in refusals[6]
    # stopped on request: not respawned, although it was started with respawn
    # (a Python child stopped while it starts up may exit 1 from its KeyboardInterrupt)
    assert "[INFO] [kid-2]: sending signal 'SIGINT' to process[kid-2]" in launcher.text
    assert "[kid-2]: process has " in launcher.text
    assert "[INFO] [kid-2]: respawning" not in launcher.text
    assert "[once-3]: process has " in launcher.text
    assert "[owner-1] owner asked for other-4" in launcher.text
    # a process outside the launch may connect but not ask
    path = launcher.wait_line("[owner-1] socket ").split()[-1]
    with SupervisorClient(path) as outsider, pytest.raises(SupervisorError) as refused:
        outsider.start("intruder", ["true"])
    assert f"process {os.getpid()} is not a process of this launch" in str(refused.value)
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    wait_gone(list(launcher.pids.values()))
    assert not Path(path).parent.exists(), "the socket's folder is removed at exit"


ANNOUNCER = """\
import sys, time
from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError

client = SupervisorClient.from_environment()
client.announce("viewer: http://127.0.0.1:1/")
for text in ("two\\nlines", "", "x" * 501):
    try:
        client.announce(text)
    except SupervisorError as error:
        print("refused:", error, file=sys.stderr, flush=True)
print("announced on stdout", flush=True)
for i in range(30):  # the rest of a bring-up's messages, after the announcement
    print("start-up message", i, file=sys.stderr, flush=True)
print("announcer done", file=sys.stderr, flush=True)
time.sleep(300)
"""
BANNER = "[INFO] [announcer-1]: viewer: http://127.0.0.1:1/"


def test_an_announcement_is_the_last_line_of_the_bring_up_whatever_the_output_mode(  # type: ignore[no-untyped-def]
    run, tmp_path
) -> None:
    script = tmp_path / "announcer.py"
    script.write_text(ANNOUNCER)
    launcher = run(f'<executable name="announcer" output="log" cmd="{sys.executable} {script}"/>')
    launcher.wait_line(BANNER)
    # held until the console settled: after every line the bring-up printed, plain (no TTY)
    assert launcher.lines.index(BANNER) > launcher.lines.index("[announcer-1] announcer done")
    assert "\033" not in launcher.text
    refusals = [line.split("refused: ", 1)[1] for line in launcher.lines if "refused: " in line]
    assert refusals == ["text must be one printable line of at most 500 characters"] * 3
    assert "announced on stdout" not in launcher.text  # output="log": stdout is not shown
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    after = launcher.lines[launcher.lines.index(BANNER) + 1]
    assert after.startswith("[WARNING] [launch]: user interrupted"), launcher.text


def test_a_requested_child_is_a_process_of_the_launch_for_the_plugin(launch, tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "t.launch.xml"
    path.write_text(f"<launch>{owner(tmp_path, then=BAD_REQUESTS_THEN_STOP)}</launch>")
    handle = launch(path)
    # "once" (no respawn) exits with SIGINT before the owner is done; the launcher said it was
    # stopping it, so that exit is not a death that fails the wait. A SIGINT that reaches a
    # Python child while it is still importing can be lost in the import system (CPython prints
    # "Exception ignored ... KeyboardInterrupt" and goes on): the launcher's SIGTERM 5 s later
    # ends it then, as ROS's escalation does (seen once, on a loaded machine).
    once_stopped = {0, 1, -2, -15}
    handle.process("owner").wait_output("owner done")
    assert handle.process("once").returncode in once_stopped
    other = handle.process("other")
    assert other.wait_output("kid up") == "kid up"
    assert other.label == "other-4"
    result = handle.stop()  # the plugin's survivor sweep includes the requested children
    result.assert_exit_codes(
        {"owner": {0, -2}, "other": {0, -2}, "once": once_stopped, "*": {0, 1, -2}}
    )
