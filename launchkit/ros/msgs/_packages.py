"""Which packages hold interface types, answered without loading any of them.

The import hook (:mod:`._importer`) is asked about every module a process imports, from the
moment the ``rclpy`` face's ``sitecustomize`` installs it; it must answer from names and folders
alone. Loading the message layer (rosbags' store, the classes) costs about 0.1 s of CPU, which a
process that never imports a message package should not pay.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path
from typing import Any

from launchkit.errors import PackageNotFoundError

KINDS = ("msg", "srv", "action")

#: the packages of the built-in store (rosbags' ROS 2 Jazzy messages and launchkit's services):
#: ``Registry.builtin_packages()`` computes them from the store itself, which a test compares
#: with this list
BUILTIN_PACKAGES = frozenset(
    {
        "action_msgs",
        "actionlib_msgs",
        "builtin_interfaces",
        "composition_interfaces",
        "diagnostic_msgs",
        "example_interfaces",
        "gazebo_msgs",
        "geometry_msgs",
        "lifecycle_msgs",
        "nav_msgs",
        "rcl_interfaces",
        "rmw_dds_common",
        "rosbag2_interfaces",
        "rosgraph_msgs",
        "sensor_msgs",
        "service_msgs",
        "shape_msgs",
        "statistics_msgs",
        "std_msgs",
        "std_srvs",
        "stereo_msgs",
        "tf2_msgs",
        "trajectory_msgs",
        "type_description_interfaces",
        "unique_identifier_msgs",
        "visualization_msgs",
    }
)


class InterfacePackages:
    """The share folders of packages with ``msg/``, ``srv/`` or ``action/`` folders, found
    through the package index and remembered."""

    def __init__(self, index: Any = None) -> None:
        """``index``: the package index to look in (default: one made from the environment
        when first needed)."""
        self._index = index
        self._folders: dict[tuple[str, bool], Path | None] = {}

    def index(self) -> Any:
        """The package index (made on first use, from the environment as it is then)."""
        if self._index is None:
            # imported when first asked: a process that imports only the standard library
            # never asks, and skips the 25 ms
            from launchkit.packages import PackageIndex

            self._index = PackageIndex()
        return self._index

    def folder(self, pkg: str, registered: bool = True) -> Path | None:
        """The share folder of ``pkg`` if it has interface folders (``registered``: also look
        at packages registered by Python distributions, which costs a first lookup)."""
        key = (pkg, registered)
        if key not in self._folders:
            self._folders[key] = self._find(pkg, registered)
        return self._folders[key]

    def _find(self, pkg: str, registered: bool) -> Path | None:
        index = self.index()
        try:
            found = index.find(pkg) if registered else index.ament_package(pkg)
        except PackageNotFoundError:
            return None
        if found is None:
            return None
        share: Path = found.share
        if any(os.path.isdir(share / kind) for kind in KINDS):
            return share
        return None


_process_packages: InterfacePackages | None = None
_lock = threading.Lock()


def interface_packages() -> InterfacePackages:
    """The process's :class:`InterfacePackages` (the registry's, unless it was given an index)."""
    global _process_packages
    with _lock:
        if _process_packages is None:
            _process_packages = InterfacePackages()
        return _process_packages
