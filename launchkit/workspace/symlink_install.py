"""``--symlink-install`` for a Python package: after pip installed it, its top-level Python
packages and modules in ``site-packages`` and its ``data_files`` become symlinks to the source,
so an edit to the source shows without building again (what colcon's ``--symlink-install``
gives through ``setup.py develop``). Console scripts stay pip's; a new script, module folder or
data file needs a build, as with colcon.

Where each installed name comes from is read from the package's setup (``packages``,
``package_dir``, ``py_modules``, ``data_files``), evaluated by setuptools itself in a child
process as far as its configuration step: nothing is built or written there.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
import tempfile
from pathlib import Path, PurePosixPath
from typing import Any

from launchkit.errors import LaunchkitError
from launchkit.workspace.ament_layout import place
from launchkit.workspace.dist_record import installed_paths, rewrite_record
from launchkit.workspace.processes import ChildProcesses

# Run in the package's folder: setup.py as far as reading its configuration, the fields that
# say where files come from written as JSON to argv[1].
_READER = """
import json, os, sys
out = sys.argv[1]
import setuptools
import distutils.core  # setuptools' own copy once setuptools is imported
if os.path.isfile("setup.py"):
    dist = distutils.core.run_setup("setup.py", script_args=[], stop_after="config")
else:
    dist = setuptools.Distribution()
    dist.parse_config_files()
data_files = []
for item in dist.data_files or []:
    data_files.append(["", [item]] if isinstance(item, str) else [item[0], list(item[1])])
with open(out, "w") as stream:
    json.dump({
        "package_dir": dict(dist.package_dir or {}),
        "data_files": data_files,
    }, stream)
"""


class SymlinkInstallError(LaunchkitError):
    """The package's setup could not be read to link its files."""


def link_to_source(
    source: Path, prefix: Path, dist_info: Path, processes: ChildProcesses, log: Path
) -> None:
    """Replace the installed Python code and data files of the package built from ``source``
    into ``prefix`` by symlinks to ``source``; keep ``dist_info``'s RECORD true."""
    setup = _read_setup(source, processes, log)
    site = dist_info.parent
    package_dir: dict[str, str] = setup["package_dir"]
    linked: list[str] = []
    for name in _top_level_names(dist_info):
        origin = _origin(source, name, package_dir)
        if origin is None:
            continue  # not where setup says (a generated module): the copy stays
        installed = site / name
        if installed.is_dir() and not installed.is_symlink():
            shutil.rmtree(installed)
        else:
            installed.unlink(missing_ok=True)
        installed.symlink_to(origin)
        linked.append(name)
    for destination, files in setup["data_files"]:
        for file in files:
            installed = prefix / destination / os.path.basename(file)
            if not os.path.isabs(destination) and installed.is_file():
                place(source / file, installed, symlink=True)
    rewrite_record(dist_info, {}, linked)


def _read_setup(source: Path, processes: ChildProcesses, log: Path) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="launchkit-build-") as folder:
        out = Path(folder) / "setup.json"
        status = processes.run([sys.executable, "-c", _READER, str(out)], source, log, os.environ)
        if status != 0 or not out.is_file():
            raise SymlinkInstallError(
                f"reading {source / 'setup.py'} for --symlink-install failed (status {status})",
                hint=f"its output: {log}",
            )
        data: dict[str, Any] = json.loads(out.read_text())
        return data


def _top_level_names(dist_info: Path) -> list[str]:
    """The top-level packages and modules pip installed (from RECORD)."""
    names: set[str] = set()
    for path in installed_paths(dist_info):
        first = PurePosixPath(path).parts[0]
        if first in ("..", "__pycache__") or first.endswith((".dist-info", ".pth")):
            continue
        names.add(first)
    return sorted(names)


def _origin(source: Path, name: str, package_dir: dict[str, str]) -> Path | None:
    root = source / package_dir.get("", "")
    if name.endswith(".py"):
        candidate = root / name
    elif name in package_dir:
        candidate = source / package_dir[name]
    else:
        candidate = root / name
    return candidate.absolute() if candidate.exists() else None
