"""What the build does with each selected package, decided before anything is built: build it
with pip (``ament_python``), install its files (an ``ament_cmake`` package that needs no
compiler), skip it (it needs CMake and a ROS install), or fail it (a dependency is missing, or
its CMakeLists.txt asks for what CMake would refuse too).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from launchkit.errors import LaunchkitError, UserError
from launchkit.workspace.cmake_plan import CMakePlan, NeedsRos, plan_cmake_package
from launchkit.workspace.known import CHECKED_KINDS, KnownPackages
from launchkit.workspace.manifest import Manifest

NEEDS_ROS = "needs a ROS install (build it with colcon)"


@dataclass(frozen=True)
class Job:
    """A package to build: with pip (``cmake is None``) or by installing its files."""

    manifest: Manifest
    cmake: CMakePlan | None = None


@dataclass(frozen=True)
class NotBuilt:
    """A package decided against before the build: ``failed`` (the errors say why) or
    skipped (``reason`` says why)."""

    manifest: Manifest
    failed: bool
    reason: str
    errors: tuple[LaunchkitError, ...] = ()


def plan_package(manifest: Manifest, known: KnownPackages) -> Job | NotBuilt:
    """The decision for one package: what kind of build first (a package launchkit cannot
    build is skipped whatever its dependencies), then its dependencies."""
    decided = _by_build_type(manifest)
    if isinstance(decided, NotBuilt):
        return decided
    missing = [d for d in manifest.depends(*CHECKED_KINDS) if not known.is_known(d.name)]
    if not missing:
        return decided
    errors = tuple(
        UserError(
            f"package '{manifest.name}' depends on '{d.name}', which is not in the "
            "workspace, not installed and not provided by launchkit",
            d.location,
            expected="a package under src/, in AMENT_PREFIX_PATH or importable by Python",
        )
        for d in missing
    )
    names = ", ".join(sorted({d.name for d in missing}))
    return NotBuilt(manifest, True, f"missing dependency: {names}", errors)


def _by_build_type(manifest: Manifest) -> Job | NotBuilt:
    if manifest.build_type == "ament_python":
        return Job(manifest)
    if manifest.build_type == "ament_cmake":
        folder = os.path.dirname(manifest.location.file)
        try:
            return Job(manifest, plan_cmake_package(manifest.path, folder))
        except NeedsRos as needs:
            return NotBuilt(manifest, False, f"{NEEDS_ROS}: {needs.reason}")
        except LaunchkitError as error:
            return NotBuilt(manifest, True, error.message, (error,))
    if manifest.build_type == "catkin":
        why = "a ROS 1 (catkin) package: its package.xml has no <export><build_type>"
    else:
        why = f"build type '{manifest.build_type}'"
    return NotBuilt(manifest, False, f"{NEEDS_ROS}: {why}")
