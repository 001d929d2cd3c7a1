"""Teardown leaves nothing behind: escalation, grandchildren, and the survivor check."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

from launchkit.testing import _procscan
from launchkit.testing._deadline import Deadline, scaled


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie waiting for its reaper does not)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat[stat.rfind(")") + 2] not in "ZX"


def test_a_child_ignoring_sigint_is_ended_by_the_escalation(launch):
    handle = launch("launch/stubborn.launch.xml")
    stubborn = handle.process("stubborn")
    very_stubborn = handle.process("very_stubborn")
    stubborn.wait_output("ignoring SIGINT", timeout=5)
    very_stubborn.wait_output("ignoring SIGINT and SIGTERM", timeout=5)

    result = handle.stop()

    # SIGTERM ended the first after its sigterm_timeout; only SIGKILL the second, both sent
    # by the launcher (the plugin's own SIGKILL would leave no exit code to report)
    result.assert_exit_codes({"stubborn": -signal.SIGTERM, "very_stubborn": -signal.SIGKILL})
    assert not _alive(stubborn.pid) and not _alive(very_stubborn.pid)
    launcher = Path(handle.launcher_log).read_text()
    assert "escalating to 'SIGTERM'" in launcher and "escalating to 'SIGKILL'" in launcher
    assert handle.stop_notes == []  # the launcher needed no help from the plugin


def test_a_grandchild_started_through_sh_does_not_survive(launch):
    handle = launch("launch/grandchild.launch.xml")
    line = handle.process("shell").wait_output("grandchild", timeout=5)
    grandchild = int(line.split()[1])
    assert _alive(grandchild)

    handle.stop()

    assert not _alive(grandchild)


def test_a_process_escaping_its_group_is_ended_by_the_launch_itself(launch):
    handle = launch("launch/escape.launch.xml")
    line = handle.process("escaper").wait_output("escaped pid", timeout=5)
    escaped = int(line.split()[-1])
    assert os.getpgid(escaped) == escaped  # left its process group, still below the launcher

    # the launch's containment (its cgroup, else the launcher as subreaper) ends it, so the
    # plugin's own check of the session (ProcessLeftBehind) finds nothing left to kill
    handle.stop()

    assert not _alive(escaped)


def test_the_last_sweep_kills_and_names_what_is_left_of_a_launchs_groups():
    # The plugin's safety net where a launch cannot contain its processes (no cgroup, no
    # subreaper): what is left of its groups after the grace is SIGKILLed and named, and the
    # teardown raises ProcessLeftBehind with those names.
    code = (
        "import signal, time; signal.signal(signal.SIGTERM, signal.SIG_IGN); "
        "print('up', flush=True); time.sleep(600)"
    )
    stubborn = subprocess.Popen(
        [sys.executable, "-c", code], start_new_session=True, stdout=subprocess.PIPE, text=True
    )
    with stubborn:
        try:
            assert stubborn.stdout is not None and stubborn.stdout.readline() == "up\n"
            left = _procscan.sweep([stubborn.pid], Deadline(0.2))
            assert [process.pid for process in left] == [stubborn.pid]
            assert "time.sleep(600)" in left[0].cmdline
            assert stubborn.wait(timeout=scaled(10)) == -signal.SIGKILL
        finally:
            stubborn.kill()  # (a no-op once it is reaped)


def test_a_hanging_launcher_is_escalated_by_the_plugin(launch):
    handle = launch("launch/talker.launch.xml")
    talker = handle.process("talker")
    talker.wait_output("talker waiting", timeout=5)
    os.kill(handle.pid, signal.SIGSTOP)  # the launcher can no longer react to anything

    result = handle.stop(timeout=0.5)

    assert "sent SIGTERM" in handle.stop_notes[0] and "SIGKILL" in handle.stop_notes[1]
    assert result.returncode == -signal.SIGKILL
    assert not _alive(talker.pid)
