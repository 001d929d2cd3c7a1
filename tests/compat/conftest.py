"""Helpers for the tests that compare launchkit with the real ROS 2 Jazzy launch.

Each test writes launch files (and, where it needs packages, a stub ament prefix) into its
temporary folder, runs ``launchkit run`` on them, and compares what it prints with what
``ros2 launch`` (launch 3.4.3, launch_ros 0.26.6) printed for the same files, recorded in the
test. Stub executables print their command line and the parameter files they are given, so
command lines and parameter files compare argument by argument.
"""

from __future__ import annotations

import re
import sys
import textwrap
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.engine.launcher import Launcher, wait_gone
from tests.engine.launcher import run_launchkit as launchkit_command

#: A stub node: prints its arguments, then each ``--params-file``'s text on one line.
STUB_NODE = textwrap.dedent(
    f"""\
    #!{sys.executable}
    import sys
    args = sys.argv[1:]
    print("argv:", " ".join(args), flush=True)
    for index, arg in enumerate(args):
        if arg == "--params-file":
            with open(args[index + 1]) as stream:
                print("params:", stream.read().replace("\\n", "|"), flush=True)
    """
)


def stub_prefix(root: Path, packages: Mapping[str, Iterable[str]]) -> Path:
    """An ament prefix at ``root`` with ``packages`` (name: its stub executables)."""
    index = root / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True, exist_ok=True)
    for name, executables in packages.items():
        (index / name).write_text("")
        share = root / "share" / name
        share.mkdir(parents=True, exist_ok=True)
        (share / "package.xml").write_text(f'<package format="3"><name>{name}</name></package>\n')
        for executable in executables:
            path = root / "lib" / name / executable
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(STUB_NODE)
            path.chmod(0o755)
    return root


@dataclass
class Ran:
    """A finished ``launchkit run``: its exit status and output lines."""

    status: int
    lines: list[str]

    @property
    def text(self) -> str:
        """The whole output."""
        return "\n".join(self.lines)

    def of(self, process: str) -> list[str]:
        """What ``process`` (``name-N``) printed, without its prefix."""
        prefix = f"[{process}] "
        return [line[len(prefix) :] for line in self.lines if line.startswith(prefix)]

    def launch_lines(self) -> list[str]:
        """The output but the lines that name the run's folder, pids or the router."""
        skipped = ("All log files can be found", "started the ROS router")
        return [
            re.sub(r"pid \d+", "pid N", re.sub(r"pid \[\d+\]", "pid [N]", line))
            for line in self.lines
            if not any(text in line for text in skipped)
        ]


def run_launch(
    cwd: Path, *args: str, env: Mapping[str, str] | None = None, timeout: float = 90.0
) -> Ran:
    """Run ``launchkit run ARGS`` in ``cwd`` to its end (killed, with all it started, after
    ``timeout`` seconds); its output, stdout and stderr in the order written."""
    private = {"ROS_LOG_DIR": str(cwd / "log"), "TMPDIR": str(cwd)}
    launcher = Launcher(*args, cwd=cwd, env={**private, **(env or {})})
    try:
        status = launcher.finish(timeout)
    finally:
        if launcher.proc.poll() is None:
            launcher.kill()
    wait_gone(list(launcher.pids.values()))
    return Ran(status, launcher.lines)


def run_launchkit(cwd: Path, *args: str, env: Mapping[str, str] | None = None) -> Ran:
    """Run another ``launchkit`` command (``check``, ``pkg list``) in ``cwd`` to its end."""
    done = launchkit_command(*args, cwd=cwd, env={"ROS_LOG_DIR": str(cwd / "log"), **(env or {})})
    return Ran(done.returncode, (done.stdout + done.stderr).splitlines())


@pytest.fixture
def launch_dir(tmp_path: Path) -> Path:
    """A folder for the test's launch files (the run's temporary files go there too)."""
    return tmp_path
