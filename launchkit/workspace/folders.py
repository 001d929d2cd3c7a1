"""The workspace's own folders, as colcon has them: ``build/`` (pip's working copies),
``install/`` (one prefix per package), ``log/`` (one folder per build, ``build_DATE_TIME``,
with a ``PKG/stdout_stderr.log`` per package, and the links ``latest_build`` and ``latest``
to the newest), each with a ``COLCON_IGNORE`` so no package search goes inside.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

IGNORE_MARKER = "COLCON_IGNORE"
#: colcon's file naming how the install folder is laid out (one prefix per package).
INSTALL_LAYOUT_FILE = ".colcon_install_layout"


def prepare_folders(build_base: Path, install_base: Path, log_base: Path) -> None:
    """Make the three folders, each with its ignore marker, and the install layout file."""
    for folder in (build_base, install_base, log_base):
        folder.mkdir(parents=True, exist_ok=True)
        (folder / IGNORE_MARKER).touch()
    (install_base / INSTALL_LAYOUT_FILE).write_text("isolated\n")


def new_log_folder(log_base: Path) -> Path:
    """A fresh ``log/build_DATE_TIME`` folder, linked as ``latest_build`` (and ``latest``)."""
    stamp = time.strftime("build_%Y-%m-%d_%H-%M-%S")
    folder = log_base / stamp
    number = 0
    while True:
        try:
            folder.mkdir(parents=True)
            break
        except FileExistsError:  # two builds in one second
            number += 1
            folder = log_base / f"{stamp}_{number}"
    _link(log_base / "latest_build", folder.name)
    _link(log_base / "latest", "latest_build")
    return folder


def _link(link: Path, target: str) -> None:
    """Point ``link`` at ``target`` (relative), replacing it in one step."""
    temporary = link.with_name(f".{link.name}.{os.getpid()}")
    temporary.unlink(missing_ok=True)
    temporary.symlink_to(target)
    os.replace(temporary, link)
