"""The files every installed package has around its own, as ament and colcon lay them out in
an isolated install (``install/PKG/`` per package):

- ``share/ament_index/resource_index/packages/PKG``: the empty marker that PKG is installed
  in this prefix (what ``ros2 pkg``, ``ament_index_python`` and launchkit's index look for);
- ``share/PKG/package.xml``;
- ``share/colcon-core/packages/PKG``: its run dependencies, ``:``-separated, as colcon writes
  them (``install/setup.sh`` orders the packages by them);
- ``share/ament_index/resource_index/rosidl_interfaces/PKG`` for an interface package: its
  interface files, one a line.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from launchkit.workspace.manifest import Manifest

INDEX = Path("share") / "ament_index" / "resource_index"
RUN_KINDS = ("depend", "exec_depend", "build_export_depend", "buildtool_export_depend")


def write_marker(prefix: Path, resource_type: str, name: str, content: str = "") -> None:
    """Register resource ``name`` of ``resource_type`` in the prefix's ament index."""
    path = prefix / INDEX / resource_type / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(content)


def has_marker(prefix: Path, name: str) -> bool:
    """Whether the prefix has package ``name``'s marker."""
    return (prefix / INDEX / "packages" / name).is_file()


def place(source: Path, target: Path, symlink: bool, executable: bool = False) -> None:
    """Put ``source`` at ``target``: a copy, or a symlink to it (``--symlink-install``);
    whatever was at ``target`` is replaced."""
    target.parent.mkdir(parents=True, exist_ok=True)
    if target.is_symlink() or target.is_file():
        target.unlink()
    elif target.is_dir():
        shutil.rmtree(target)
    if symlink:
        target.symlink_to(os.path.abspath(source))
        return
    shutil.copy2(source, target)
    if executable:
        target.chmod(target.stat().st_mode | 0o111)


def finish_layout(manifest: Manifest, prefix: Path, symlink: bool) -> None:
    """The marker, package.xml and run dependencies of ``manifest``'s package, each written
    unless the package's own install already put it there (colcon does the same)."""
    if not has_marker(prefix, manifest.name):
        write_marker(prefix, "packages", manifest.name)
    installed = prefix / "share" / manifest.name / "package.xml"
    if not installed.exists():
        place(manifest.manifest_path, installed, symlink)
    run = sorted({d.name for d in manifest.depends(*RUN_KINDS)})
    colcon = prefix / "share" / "colcon-core" / "packages" / manifest.name
    colcon.parent.mkdir(parents=True, exist_ok=True)
    colcon.write_text(":".join(run))


def run_dependencies(prefix: Path, name: str) -> list[str]:
    """What ``share/colcon-core/packages/NAME`` of the prefix lists (none if absent)."""
    try:
        text = (prefix / "share" / "colcon-core" / "packages" / name).read_text()
    except OSError:
        return []
    return [d for d in text.strip().split(":") if d]


def python_paths(prefix: Path) -> list[Path]:
    """The prefix's folders of Python packages (``lib/python3.X/site-packages`` for the pip
    layout, ``dist-packages`` or ``local/lib/...`` for Debian's), sorted."""
    found: list[Path] = []
    for pattern in ("lib/python3*/*-packages", "local/lib/python3*/dist-packages"):
        found.extend(p for p in prefix.glob(pattern) if p.is_dir())
    return sorted(found)


def installed_packages(install_base: Path) -> list[str]:
    """The packages of an isolated install folder: each ``install/PKG`` with PKG's marker."""
    if not install_base.is_dir():
        return []
    return sorted(
        entry.name
        for entry in install_base.iterdir()
        if entry.is_dir() and has_marker(entry, entry.name)
    )
