"""Building an ``ament_python`` package: pip builds and installs it into ``install/PKG``
(``pip install --prefix``), and the ament layout is written around what pip installed.

The source is copied to ``build/PKG`` first and pip builds the copy, so setuptools' own
``build/`` and ``*.egg-info`` folders land there and never in the source (colcon keeps the
source clean the same way). pip runs offline, without build isolation and without installing
dependencies: the build uses the setuptools of launchkit's own environment.

pip puts console scripts in ``PREFIX/bin``; a package whose ``setup.cfg`` says where its
scripts go (``[install] install_scripts=$base/lib/PKG``, what ``ros2 pkg create`` writes, or
``[develop] script_dir``) gets them moved there, where ``ros2 run`` and ``launchkit exec``
look. Without it they stay in ``bin/``, which ``install/setup.sh`` puts on ``PATH``.
"""

from __future__ import annotations

import configparser
import os
import re
import shutil
import sys
from pathlib import Path

from launchkit.errors import LaunchkitError, Location
from launchkit.workspace.ament_layout import finish_layout, python_paths
from launchkit.workspace.dist_record import find_dist_info, installed_paths, rewrite_record
from launchkit.workspace.manifest import Manifest
from launchkit.workspace.processes import ChildProcesses
from launchkit.workspace.symlink_install import link_to_source

PIP_INSTALL = [
    "install",
    "--no-deps",
    "--no-build-isolation",
    "--no-index",
    "--ignore-installed",
    "--no-cache-dir",
    "--disable-pip-version-check",
    "--no-input",
    "--no-warn-script-location",
]
#: Lines of pip's output shown under a failure (after its first error line).
TAIL_LINES = 20
_SETUP_FILES = ("setup.py", "setup.cfg", "pyproject.toml")
#: pip settings from the environment that would send the install elsewhere than the prefix.
_PIP_PLACES = ("PIP_USER", "PIP_TARGET", "PIP_PREFIX", "PIP_ROOT", "PIP_REQUIRE_VIRTUALENV")
_PREFIX_VARIABLE = re.compile(r"\$(\{(base|prefix|exec_prefix|platbase)\}|base|prefix|platbase)")


class BuildFailure(LaunchkitError):
    """A package failed to build; ``quoted`` holds what the failing tool said."""


def build_python_package(
    manifest: Manifest,
    prefix: Path,
    staging: Path,
    log: Path,
    processes: ChildProcesses,
    symlink: bool,
) -> None:
    """Build and install ``manifest``'s package into ``prefix``; :class:`BuildFailure` if
    pip fails (with pip's first error line and its last lines)."""
    source = manifest.path
    if not any((source / name).is_file() for name in _SETUP_FILES):
        raise BuildFailure(
            "an ament_python package without setup.py",
            manifest.location,
            expected="setup.py (or setup.cfg, pyproject.toml) beside package.xml",
        )
    _fresh_copy(source, staging)
    remove_prefix(prefix)
    argv = [sys.executable, "-m", "pip", *PIP_INSTALL, "--prefix", str(prefix), str(staging)]
    env = {k: v for k, v in os.environ.items() if k not in _PIP_PLACES}
    status = processes.run(argv, staging, log, env)
    if status != 0:
        raise pip_failure(status, log, {str(staging): str(source)})
    sites = python_paths(prefix)
    dist_info = find_dist_info(sites[0]) if sites else None
    scripts = _script_folder(source, prefix)
    if scripts is not None and dist_info is not None:
        _move_scripts(prefix, scripts, dist_info)
    if symlink and dist_info is not None:
        link_to_source(source, prefix, dist_info, processes, log)
    finish_layout(manifest, prefix, symlink)


def remove_prefix(prefix: Path) -> None:
    """Empty the package's install prefix (pip does not remove what an earlier build left);
    a symlink is removed, never followed."""
    if prefix.is_symlink() or prefix.is_file():
        prefix.unlink()
    elif prefix.is_dir():
        shutil.rmtree(prefix)


def pip_failure(status: int, log: Path, renames: dict[str, str]) -> BuildFailure:
    """The failure pip's exit ``status`` and output (in ``log``) make; ``renames`` maps the
    working copy's path to the source's, so the lines shown name the files to edit."""
    text = log.read_text(encoding="utf-8", errors="replace")
    for copy, source in renames.items():
        text = text.replace(copy, source)
    lines = text.splitlines()
    tail = [line.rstrip() for line in lines[-TAIL_LINES:] if line.strip()]
    first = next((line.strip() for line in lines if re.match(r"\s*(ERROR|error)\b", line)), None)
    quoted = ([first, "..."] if first is not None and first not in tail else []) + tail
    return BuildFailure(
        f"pip exited with status {status}",
        quoted=quoted,
        hint=f"pip's whole output: {log}",
    )


def _fresh_copy(source: Path, staging: Path) -> None:
    remove_prefix(staging)
    top = os.path.realpath(source)

    def leave_out(folder: str, names: list[str]) -> set[str]:
        skipped = {n for n in names if n in ("__pycache__", ".git") or n.endswith(".egg-info")}
        if os.path.realpath(folder) == top:  # setuptools' outputs of a build by hand
            skipped.update(n for n in names if n in ("build", "dist"))
        return skipped

    shutil.copytree(source, staging, ignore=leave_out, ignore_dangling_symlinks=True)


def _script_folder(source: Path, prefix: Path) -> Path | None:
    """Where ``setup.cfg`` says scripts go, with ``$base`` as the prefix; None if it does not
    say. A folder outside the prefix is refused."""
    config = configparser.ConfigParser(interpolation=None)
    try:
        config.read(source / "setup.cfg", encoding="utf-8")
    except configparser.Error as error:
        raise BuildFailure(
            f"setup.cfg cannot be read: {error}", Location(str(source / "setup.cfg"))
        ) from None
    for section, keys in (
        ("install", ("install_scripts", "install-scripts")),
        ("develop", ("script_dir", "script-dir")),
    ):
        for key in keys:
            value = config.get(section, key, fallback=None)
            if value:
                folder = Path(_PREFIX_VARIABLE.sub(lambda _: str(prefix), value.strip()))
                folder = folder if folder.is_absolute() else prefix / folder
                if not os.path.normpath(folder).startswith(os.path.normpath(prefix) + os.sep):
                    raise BuildFailure(
                        f"setup.cfg's [{section}] {key} = {value} is outside the install prefix",
                        Location(str(source / "setup.cfg")),
                        expected="$base/lib/PACKAGE",
                    )
                return folder
    return None


def _move_scripts(prefix: Path, scripts: Path, dist_info: Path) -> None:
    """Move the scripts pip installed (into ``bin/``, or ``local/bin/`` in Debian's scheme,
    as its RECORD says) to ``scripts``, keeping RECORD true."""
    site = dist_info.parent
    bins = {str(prefix / "bin"), str(prefix / "local" / "bin")} - {str(scripts)}
    moved: dict[str, str] = {}
    for written in installed_paths(dist_info):
        path = Path(os.path.normpath(site / written))
        if str(path.parent) in bins and path.is_file():
            scripts.mkdir(parents=True, exist_ok=True)
            target = scripts / path.name
            path.rename(target)
            moved[written] = _record_path(target, site)
    for folder in bins:
        if os.path.isdir(folder) and not os.listdir(folder):
            os.rmdir(folder)
    rewrite_record(dist_info, moved)


def _record_path(path: Path, site: Path) -> str:
    return Path(os.path.relpath(path, site)).as_posix()
