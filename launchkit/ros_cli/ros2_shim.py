"""A ``ros2`` command for the processes launchkit starts, where no ROS 2 is installed.

Launch files call ``ros2`` (``FindExecutable(name='ros2')``, ``<executable cmd="ros2 param set
...">``, as the ROS 2 tutorials' event-handler example does). When no ``ros2`` is on the PATH,
launchkit appends a folder holding a small ``ros2`` script to the PATH of the launch and of
``launchkit exec``: ``ros2 VERB ...`` then runs ``launchkit VERB ...`` (``ros2 run`` is
``launchkit exec``). The folder goes *after* everything on the PATH, and only when no ``ros2`` is
found there, so a real ROS 2 is never shadowed. ``launchkit shell-init`` prints the line that
does the same for a user's shell.

The folder is in the user's runtime folder (:func:`launchkit.ros.rundir.runtime_dir`), one per
Python interpreter (the script runs ``python -m launchkit`` with the interpreter that wrote it).
"""

from __future__ import annotations

import hashlib
import os
import shlex
import shutil
import sys
from collections.abc import Mapping
from pathlib import Path

from launchkit.ros.rundir import RunDirError, runtime_dir

COMMAND = "ros2"


def _script() -> str:
    python = shlex.quote(sys.executable)
    return (
        "#!/bin/sh\n"
        "# `ros2 VERB ...` runs launchkit's VERB (`ros2 run` is `launchkit exec`). Written by\n"
        "# launchkit for the processes it starts where no ROS 2 is installed; safe to delete.\n"
        'if [ "$1" = run ]; then shift; set -- exec "$@"; fi\n'
        f'exec {python} -m launchkit "$@"\n'
    )


def shim_folder() -> Path:
    """The folder with the ``ros2`` script, written (again) if it is missing or stale."""
    digest = hashlib.sha256(sys.executable.encode()).hexdigest()[:12]
    folder = runtime_dir() / f"ros2-shim-{digest}"
    folder.mkdir(mode=0o700, exist_ok=True)
    script = folder / COMMAND
    text = _script()
    try:
        current = script.read_text(encoding="utf-8")
    except OSError:
        current = ""
    if current != text or not os.access(script, os.X_OK):
        temporary = folder / f".{COMMAND}.{os.getpid()}"
        temporary.write_text(text, encoding="utf-8")
        temporary.chmod(0o755)
        os.replace(temporary, script)  # atomic: a process starting now sees one or the other
    return folder


def with_ros2(environ: Mapping[str, str]) -> dict[str, str]:
    """``environ`` with the shim folder at the end of its ``PATH``, unless a ``ros2`` is on
    that PATH already (or the runtime folder cannot be used: then no shim, and a launch file
    that needs ``ros2`` says it is not found, as it would without launchkit)."""
    environment = dict(environ)
    path = environment.get("PATH", os.defpath)
    if shutil.which(COMMAND, path=path) is not None:
        return environment
    try:
        folder = str(shim_folder())
    except (OSError, RunDirError):
        return environment
    environment["PATH"] = os.pathsep.join([*path.split(os.pathsep), folder])
    return environment


def shell_init() -> str:
    """The shell lines that give a shell the same ``ros2`` (``eval "$(launchkit shell-init)"``):
    the shim folder appended to its PATH, so a ROS 2 install sourced before or after wins."""
    folder = shlex.quote(str(shim_folder()))
    lines = [
        "# launchkit: `ros2 VERB ...` runs `launchkit VERB ...` when no ROS 2 `ros2` comes first",
        f'export PATH="$PATH":{folder}',
    ]
    found = shutil.which(COMMAND)
    if found is not None:
        lines.insert(1, f"# (a ros2 is on the PATH already, {found}: it stays the one that runs)")
    return "\n".join(lines)
