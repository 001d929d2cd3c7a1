"""A signal that arrives while a ``$(command)`` is being started (after the fork, before
``Popen`` returns) still kills the command: it is held until the command's process group is
known, then raised (issue #17, point 2; seen in CI as a ``sleep`` outliving a timer's Ctrl-C).

Both ways of evaluating with signals on are covered: the supervisor's loop (``launchkit run``)
and ``--print``/``check`` (``api.dry_run``). The signal is sent by the launcher process itself,
from inside ``Popen``, once the command is running: the worst moment, made certain rather than
waited for.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from launchkit import api
from tests.engine.launcher import wait_gone

#: Replaces ``subprocess.Popen`` in a launcher (``MARKER`` defined before it): once the command
#: whose argv mentions the marker file has written its pid there, the launcher sends itself
#: SIGINT, still inside Popen.
SIGNAL_INSIDE_POPEN = """
import os, pathlib, signal, subprocess, time

real = subprocess.Popen


class SignalledPopen(real):
    def __init__(self, args, *rest, **options):
        super().__init__(args, *rest, **options)
        if any(MARKER in str(arg) for arg in args):
            deadline = time.monotonic() + 30
            marker = pathlib.Path(MARKER)
            while time.monotonic() < deadline and not (
                marker.exists() and marker.read_text().strip()
            ):
                time.sleep(0.02)
            os.kill(os.getpid(), signal.SIGINT)


subprocess.Popen = SignalledPopen
"""


def _command_file(tmp_path: Path, marker: Path) -> Path:
    command = f"sh -c &quot;echo $$ &gt; {marker}; exec sleep 300&quot;"
    path = tmp_path / "command.launch.xml"
    path.write_text(f"<launch><log message=\"$(command '{command}')\"/></launch>\n")
    return path


def _pid(marker: Path) -> int:
    text = marker.read_text().strip() if marker.exists() else ""
    assert text, f"the command never wrote its pid to {marker}"
    return int(text)


def test_a_signal_while_a_command_starts_under_the_supervisor_kills_it(tmp_path: Path) -> None:
    marker = tmp_path / "pid"
    script = (
        f"MARKER = {str(marker)!r}\n"
        + SIGNAL_INSIDE_POPEN
        + "import sys\nfrom launchkit.cli import main\n"
        + f"sys.exit(main(['run', {str(_command_file(tmp_path, marker))!r}]))\n"
    )
    launcher = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=False
    )
    assert launcher.returncode == 0, launcher.stderr
    wait_gone([_pid(marker)])


def test_a_signal_while_a_command_starts_under_print_kills_it(tmp_path: Path) -> None:
    marker = tmp_path / "pid"
    real = subprocess.Popen
    try:
        exec(SIGNAL_INSIDE_POPEN, {"MARKER": str(marker)})  # patches subprocess.Popen here
        with pytest.raises(KeyboardInterrupt):
            api.dry_run(_command_file(tmp_path, marker))
    finally:
        subprocess.Popen = real  # type: ignore[misc]
    wait_gone([_pid(marker)])
