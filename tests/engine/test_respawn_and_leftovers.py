"""What a launch leaves behind, however it ends (issue #17, points 6 and 7): respawn backs off
after quick failures, a respawning child's leftovers go before its next start, a SIGKILLed
launcher leaves no process and no temporary folder, a missing ``cwd`` is named as such."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

from tests.engine.launcher import alive, wait_gone


def _survivors(token: str) -> list[int]:
    """Processes whose command line holds ``token``."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as cmdline:
                if token.encode() in cmdline.read() and alive(int(entry)):
                    found.append(int(entry))
        except OSError:
            continue
    return found


def _wait_no_survivors(token: str, timeout: float = 15.0) -> None:
    deadline = time.monotonic() + timeout
    while (left := _survivors(token)) and time.monotonic() < deadline:
        time.sleep(0.05)
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    assert not left, f"processes {left} survived (killed now)"


def test_an_instantly_failing_respawn_backs_off(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run('<executable name="crash" cmd="false" respawn="true" respawn_delay="0"/>')
    # ROS restarts it ~825 times a second; here the waits double: 0.1, 0.2, 0.4, 0.8, 1.6 s
    launcher.wait_line("backing off: 5 exits soon after start")
    assert launcher.text.count("process started with pid") == 5
    assert "respawning in 0.1 s" in launcher.text and "respawning in 1.6 s" in launcher.text
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0


def test_a_respawning_childs_leftovers_go_before_its_next_start(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        '<executable name="leaky" output="screen" respawn="true" respawn_delay="0" '
        "cmd=\"sh -c 'sleep 300 &amp; echo grandchild $!; exit 1'\"/>"
    )
    grandchildren = [
        int(launcher.wait_line("[leaky-1] grandchild", count=n).split()[-1]) for n in (1, 2, 3, 4)
    ]
    wait_gone(grandchildren[:3])  # they used to pile up, one per incarnation
    launcher.signal(signal.SIGINT)
    assert launcher.finish() == 0
    wait_gone([*grandchildren, *launcher.pids.values()])


def test_sigkill_of_the_launcher_during_respawns_leaves_nothing(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    token = f"{900000 + os.getpid() % 1000}.{uuid.uuid4().int % 10**6}"
    for trial in range(3):
        launcher = run(
            f'<executable name="leaky{trial}" output="screen" respawn="true" respawn_delay="0" '
            f"cmd=\"sh -c 'sleep {token} &amp; echo grandchild $!; exit 1'\"/>"
        )
        launcher.wait_line(f"[leaky{trial}-1] grandchild", count=2 + trial)
        os.kill(launcher.proc.pid, signal.SIGKILL)
        launcher.proc.wait(10)
        _wait_no_survivors(token)


GATED = """
import os, signal, sys
from launchkit.description.process_spec import ProcessSpec
from launchkit.runtime.process import ManagedProcess

marker = sys.argv[1]
spec = ProcessSpec("victim", ["sh", "-c", f"touch {marker}; exec sleep 300"], dict(os.environ))

def launcher_dies(pgid):  # the launcher is SIGKILLed before the guard has heard of the group
    print(pgid, flush=True)
    os.kill(os.getpid(), signal.SIGKILL)

ManagedProcess(spec, "victim-1", 1, launcher_dies).spawn()
"""


def test_a_child_never_runs_before_the_orphan_guard_knows_its_group(tmp_path: Path) -> None:
    marker = tmp_path / "ran"
    helper = subprocess.run(
        [sys.executable, "-c", GATED, str(marker)], capture_output=True, text=True, timeout=60
    )
    assert helper.returncode == -signal.SIGKILL, helper.stderr
    child = int(helper.stdout.strip())
    wait_gone([child])  # the gate read end-of-file: the program was never started
    assert not marker.exists()


def test_sigkill_of_the_launcher_removes_its_temporary_files(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    prefix = tmp_path / "ament"
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "fake").touch()
    (prefix / "share" / "fake").mkdir()
    (prefix / "lib" / "fake").mkdir(parents=True)
    tool = prefix / "lib" / "fake" / "tool"
    # prints its parameters file, puts a file of its own in the launch's private folder
    tool.write_text(
        '#!/bin/sh\nwhile [ "$1" != --params-file ]; do shift; done\n'
        'touch "$LAUNCHKIT_RUN_TMPDIR/mine"\necho "params $2"\nexec sleep 300\n'
    )
    tool.chmod(0o755)
    os.environ["AMENT_PREFIX_PATH"] = str(prefix)
    try:
        launcher = run(
            '<node pkg="fake" exec="tool" name="n" output="screen">'
            '<param name="gain" value="2"/></node>'
        )
        params = Path(launcher.wait_line("params ").split()[-1])
    finally:
        del os.environ["AMENT_PREFIX_PATH"]
    assert "gain" in params.read_text()
    folder = params.parent.parent
    assert (folder / "mine").exists() and folder.name.startswith("launchkit-")
    os.kill(launcher.proc.pid, signal.SIGKILL)
    launcher.proc.wait(10)
    wait_gone(list(launcher.pids.values()))
    deadline = time.monotonic() + 15
    while folder.exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not folder.exists(), f"{folder} is left after the launcher was SIGKILLed"


def test_a_missing_cwd_is_named_as_such(run, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    # as ROS (tests/compat/test_process_failures.py): that process fails, the launch goes on
    launcher = run(f'<executable cmd="true" cwd="{tmp_path / "nowhere"}"/>')
    assert launcher.finish() == 0
    assert f"its working folder '{tmp_path / 'nowhere'}' does not exist" in launcher.text
    assert "not found" not in launcher.text and "Traceback" not in launcher.text
