"""The per-run log directory: ``$ROS_LOG_DIR`` or ``~/.launchkit/log``, one folder per run,
with a ``latest`` link."""

from __future__ import annotations

import datetime
import os
import socket
from collections.abc import Mapping
from pathlib import Path


def log_root(environment: Mapping[str, str]) -> Path:
    """Where run folders go: ``ROS_LOG_DIR``, else ``~/.launchkit/log``."""
    configured = environment.get("ROS_LOG_DIR")
    if configured:
        return Path(configured).expanduser()
    return Path(environment.get("HOME", "~")).expanduser() / ".launchkit" / "log"


def create_run_dir(environment: Mapping[str, str]) -> Path:
    """Make this run's folder (``<stamp>-<host>-<pid>``) and point ``latest`` at it."""
    root = log_root(environment)
    stamp = datetime.datetime.now().strftime("%Y-%m-%d-%H-%M-%S-%f")
    run_dir = root / f"{stamp}-{socket.gethostname()}-{os.getpid()}"
    run_dir.mkdir(parents=True, exist_ok=True)
    latest = root / "latest"
    try:
        tmp = root / f".latest-{os.getpid()}"
        tmp.unlink(missing_ok=True)
        tmp.symlink_to(run_dir.name)
        tmp.replace(latest)
    except OSError:
        pass  # a read-only or odd file system: the run folder itself is what matters
    return run_dir
