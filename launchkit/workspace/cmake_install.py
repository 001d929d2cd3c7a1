"""Installing an ``ament_cmake`` package that needs no compiler (see
:mod:`launchkit.workspace.cmake_plan`): its interface files into ``share/PKG/msg|srv|action``
with the ``rosidl_interfaces`` index entry rosidl writes, its ``install()`` rules, then the
ament layout around them.

rosidl also installs ``.idl`` files it generates from each ``.msg``/``.srv``/``.action``
(rosidl_adapter); nothing here generates them, so the index lists the files as written.
"""

from __future__ import annotations

import fnmatch
import os
from pathlib import Path

from launchkit.workspace.ament_layout import finish_layout, place, write_marker
from launchkit.workspace.cmake_plan import CMakeError, CMakePlan
from launchkit.workspace.cmake_rules import InstallRule
from launchkit.workspace.manifest import Manifest

INTERFACE_GROUP = "rosidl_interface_packages"


def install_cmake_package(
    manifest: Manifest, plan: CMakePlan, prefix: Path, symlink: bool
) -> list[str]:
    """Install the package into ``prefix``; the installed paths, relative to it.
    :class:`CMakeError` for what CMake would refuse too."""
    installed: list[str] = []
    if plan.interfaces is not None:
        if plan.group_check and INTERFACE_GROUP not in manifest.groups:
            raise CMakeError(
                "a package installing interfaces must be a member of "
                f"'{INTERFACE_GROUP}' (rosidl_generate_interfaces stops here too)",
                manifest.location,
                expected=f"<member_of_group>{INTERFACE_GROUP}</member_of_group>",
            )
        share = prefix / "share" / manifest.name
        for interface in plan.interfaces:
            place(interface.source, share / interface.installed_as, symlink)
        names = sorted(i.installed_as for i in plan.interfaces)
        write_marker(prefix, "rosidl_interfaces", manifest.name, "\n".join(names))
        installed.extend(f"share/{manifest.name}/{name}" for name in names)
    for rule in plan.installs:
        installed.extend(_install(rule, manifest.path, prefix, symlink))
    finish_layout(manifest, prefix, symlink)
    return installed


def _install(rule: InstallRule, folder: Path, prefix: Path, symlink: bool) -> list[str]:
    destination = prefix / rule.destination
    placed: list[Path] = []
    for written in rule.sources:
        source = Path(written) if os.path.isabs(written) else folder / written
        if rule.kind == "DIRECTORY":
            if not source.is_dir():
                if rule.optional:
                    continue
                raise CMakeError(f"install(DIRECTORY): '{written}' is not a folder", rule.location)
            # "dir/" installs the folder's contents, "dir" the folder itself
            target = destination if written.endswith("/") else destination / source.name
            placed.extend(_install_tree(rule, source, target, symlink))
        else:
            if not source.is_file():
                if rule.optional:
                    continue
                raise CMakeError(f"install({rule.kind}): '{written}' does not exist", rule.location)
            target = destination / (rule.rename or source.name)
            place(source, target, symlink, rule.executable)
            placed.append(target)
    return [str(p.relative_to(prefix)) for p in placed]


def _install_tree(rule: InstallRule, source: Path, target: Path, symlink: bool) -> list[Path]:
    placed: list[Path] = []
    target.mkdir(parents=True, exist_ok=True)
    for root, dirs, files in os.walk(source):
        here = Path(root)
        dirs[:] = sorted(d for d in dirs if not _excluded(rule, d))
        for directory in dirs:
            (target / (here / directory).relative_to(source)).mkdir(parents=True, exist_ok=True)
        for name in sorted(files):
            if _excluded(rule, name) or (rule.files_matching and not _matching(rule, name)):
                continue
            path = here / name
            installed = target / path.relative_to(source)
            place(path, installed, symlink, rule.executable)  # a copy keeps the file's mode
            placed.append(installed)
    return placed


def _excluded(rule: InstallRule, name: str) -> bool:
    return any(excluded and fnmatch.fnmatchcase(name, glob) for glob, excluded in rule.patterns)


def _matching(rule: InstallRule, name: str) -> bool:
    return any(not excluded and fnmatch.fnmatchcase(name, glob) for glob, excluded in rule.patterns)
