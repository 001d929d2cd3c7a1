"""The per-run log directory: ``$ROS_LOG_DIR`` or ``~/.launchkit/log``, one folder per run,
with a ``latest`` link, and the limits on what the logs may take (:class:`LogLimits`).

A run folder holds a marker file, :data:`RUN_MARKER`, locked for as long as its launcher runs.
When a run starts, the oldest launchkit run folders beyond ``keep_runs`` are removed; folders
without the marker (ROS's own, when ``ROS_LOG_DIR`` is shared) and folders whose marker is still
locked (a launch still running) are never touched.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from launchkit.envvars import LOG_FILE_MB, LOG_KEEP_RUNS, LOG_RUN_MB
from launchkit.errors import UserError

RUN_MARKER = ".launchkit-run"
_MB = 1024 * 1024


@dataclass(frozen=True)
class LogLimits:
    """How much a run may log: a file's size before it is rotated (bytes, 0: never), a run
    folder's size after which child output is no longer logged (bytes, 0: no limit), and how
    many run folders are kept (0: all)."""

    file_bytes: int = 50 * _MB
    run_bytes: int = 1000 * _MB
    keep_runs: int = 50

    @classmethod
    def from_environment(cls, environment: Mapping[str, str]) -> LogLimits:
        """The limits ``LAUNCHKIT_LOG_*`` set; :class:`UserError` for a value that is no number."""
        default = cls()
        return cls(
            file_bytes=_megabytes(environment, LOG_FILE_MB, default.file_bytes),
            run_bytes=_megabytes(environment, LOG_RUN_MB, default.run_bytes),
            keep_runs=int(_number(environment, LOG_KEEP_RUNS, default.keep_runs, whole=True)),
        )


def _number(environment: Mapping[str, str], name: str, default: float, *, whole: bool) -> float:
    text = environment.get(name, "").strip()
    if not text:
        return default
    try:
        value = int(text) if whole else float(text)
    except ValueError:
        value = -1
    if value < 0:
        kind = "a whole number" if whole else "a number of megabytes"
        raise UserError(f"{name}={text!r} is not valid", expected=f"{kind} >= 0 (0: no limit)")
    return value


def _megabytes(environment: Mapping[str, str], name: str, default: int) -> int:
    return int(_number(environment, name, default / _MB, whole=False) * _MB)


def log_root(environment: Mapping[str, str]) -> Path:
    """Where run folders go: ``ROS_LOG_DIR``, else ``~/.launchkit/log``."""
    configured = environment.get("ROS_LOG_DIR")
    if configured:
        return Path(configured).expanduser()
    return Path(environment.get("HOME", "~")).expanduser() / ".launchkit" / "log"


@dataclass
class RunDir:
    """A run's log folder, and the open marker that says it is in use."""

    path: Path
    marker_fd: int

    def release(self) -> None:
        """The run is over: its folder may be pruned by later runs."""
        if self.marker_fd >= 0:
            os.close(self.marker_fd)
            self.marker_fd = -1


def create_run_dir(environment: Mapping[str, str], keep_runs: int | None = None) -> RunDir:
    """Make this run's folder (``<stamp>-<host>-<pid>``), point ``latest`` at it, and remove
    the oldest finished launchkit runs beyond ``keep_runs`` (default: from the environment)."""
    root = log_root(environment)
    now = time.time()  # as datetime's "%Y-%m-%d-%H-%M-%S-%f", without importing datetime
    stamp = time.strftime("%Y-%m-%d-%H-%M-%S", time.localtime(now)) + f"-{int(now % 1 * 1e6):06d}"
    run_dir = root / f"{stamp}-{os.uname().nodename}-{os.getpid()}"  # socket.gethostname()
    run_dir.mkdir(parents=True, exist_ok=True)
    marker = os.open(run_dir / RUN_MARKER, os.O_RDWR | os.O_CREAT, 0o644)
    fcntl.flock(marker, fcntl.LOCK_EX)
    latest = root / "latest"
    try:
        tmp = root / f".latest-{os.getpid()}"
        tmp.unlink(missing_ok=True)
        tmp.symlink_to(run_dir.name)
        tmp.replace(latest)
    except OSError:
        pass  # a read-only or odd file system: the run folder itself is what matters
    if keep_runs is None:
        keep_runs = LogLimits.from_environment(environment).keep_runs
    prune_runs(root, keep_runs)
    return RunDir(run_dir, marker)


def prune_runs(root: Path, keep: int) -> list[Path]:
    """Remove the oldest finished launchkit run folders of ``root`` so that at most ``keep``
    remain (0: keep all); the removed folders."""
    if keep <= 0:
        return []
    try:
        entries = list(root.iterdir())
    except OSError:
        return []
    runs = sorted(p for p in entries if not p.is_symlink() and (p / RUN_MARKER).is_file())
    removed: list[Path] = []
    for run in runs[: max(0, len(runs) - keep)]:
        if _finished(run):
            shutil.rmtree(run, ignore_errors=True)
            removed.append(run)
    return removed


def _finished(run: Path) -> bool:
    """Whether no launcher holds ``run``'s marker."""
    try:
        fd = os.open(run / RUN_MARKER, os.O_RDONLY)
    except OSError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False
    finally:
        os.close(fd)
    return True
