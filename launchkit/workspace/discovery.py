"""Finding a workspace's packages: every folder holding a ``package.xml`` under the base
paths, at any depth, as colcon finds them.

A folder holding ``COLCON_IGNORE`` (or ``AMENT_IGNORE``, ``CATKIN_IGNORE``) is not searched,
nor are hidden folders; the search does not go inside a package. Two packages of one name are
a mistake (exit status 2), as for colcon.
"""

from __future__ import annotations

import os
from pathlib import Path

from launchkit.errors import UserError
from launchkit.workspace.manifest import Manifest, read_manifest

IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")


def find_packages(base_paths: list[Path], skip: list[Path] | None = None) -> list[Manifest]:
    """The packages under ``base_paths`` (sorted by name); ``skip`` lists folders never
    searched (the workspace's own build, install and log folders)."""
    skipped = {_real(p) for p in skip or []}
    found: dict[str, Manifest] = {}
    seen: set[str] = set()
    for base in base_paths:
        if not base.is_dir():
            raise UserError(
                f"base path '{base}' is not a folder",
                expected="a folder holding packages (a package.xml in each)",
            )
        for folder in _package_folders(base, skipped, seen):
            manifest = read_manifest(folder / "package.xml")
            other = found.get(manifest.name)
            if other is not None:
                raise UserError(
                    f"two packages are named '{manifest.name}': {other.path} and {folder}",
                    manifest.location,
                    expected="one package of each name (put COLCON_IGNORE in the one to leave out)",
                )
            found[manifest.name] = manifest
    return [found[name] for name in sorted(found)]


def _package_folders(base: Path, skipped: set[str], seen: set[str]) -> list[Path]:
    folders: list[Path] = []
    for root, dirs, files in os.walk(base, followlinks=True):
        real = _real(Path(root))
        if real in seen or real in skipped or any(m in files for m in IGNORE_MARKERS):
            dirs.clear()  # a symlink loop, an ignored folder, or the build's own output
            continue
        seen.add(real)
        if "package.xml" in files:
            folders.append(Path(root))
            dirs.clear()
            continue
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "__pycache__")
    return folders


def _real(path: Path) -> str:
    return os.path.realpath(path)
