"""Which dependencies a build checks, and whether each is there.

Checked: ``depend``, ``build_depend`` and ``exec_depend`` (format 1's ``run_depend``): the
packages a package is built against or runs with. Not checked: ``test_depend`` and
``doc_depend`` (nothing here runs tests or builds docs), ``buildtool_depend`` (the build tool
is launchkit), ``build_export_depend`` and ``buildtool_export_depend`` (what a package's C++
users would need).

A checked dependency is there when it is, in this order:

1. a package of the workspace;
2. a package launchkit's package index finds (its stock packages, registered Python
   distributions, ``AMENT_PREFIX_PATH``);
3. a package whose messages launchkit knows (its built-in type store);
4. an importable top-level Python package of that name (``ament_index_python``,
   ``sensor_msgs_py`` installed with pip);
5. one of the :data:`PROVIDED` names, or a rosdep key or build tool: a name starting with
   one of :data:`SYSTEM_PREFIXES` (``python3-numpy``, ``ament_cmake``, ``rosidl_...``),
   which are installed by pip or are launchkit's own job.

Anything else is missing, and the package that asks for it is not built.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Callable

from launchkit.packages import PackageIndex

CHECKED_KINDS = ("depend", "build_depend", "exec_depend")

#: Names of ROS packages that launchkit itself stands in for (the rclpy face, the launch
#: stand-ins, tf2, sensor_msgs_py), whatever else is installed.
PROVIDED = frozenset(
    {
        "rclpy",
        "launch",
        "launch_ros",
        "launch_xml",
        "launch_yaml",
        "launch_testing",
        "launch_testing_ros",
        "launch_testing_ament_cmake",
        "ros2launch",
        "tf2_ros",
        "tf2_ros_py",
        "tf2_geometry_msgs",
        "sensor_msgs_py",
    }
)
#: rosdep keys of Python packages (installed with pip) and ROS build tools.
SYSTEM_PREFIXES = ("python3-", "python-", "ament_", "rosidl_")


class KnownPackages:
    """Answers "is dependency NAME there?" for the packages of one workspace; each source is
    asked only when the ones before it do not know the name."""

    def __init__(
        self,
        workspace: set[str],
        index: PackageIndex | None = None,
        type_store: Callable[[], set[str]] | None = None,
    ) -> None:
        self._workspace = workspace
        self._index = index if index is not None else PackageIndex()
        self._type_store_source = type_store if type_store is not None else _type_store_packages
        self._indexed: set[str] | None = None
        self._type_store: set[str] | None = None

    def is_known(self, name: str) -> bool:
        """Whether dependency ``name`` is there (see the module's docstring for the order)."""
        if name in self._workspace or name in PROVIDED or name.startswith(SYSTEM_PREFIXES):
            return True
        if self._indexed is None:
            self._indexed = set(self._index.names())
        if name in self._indexed:
            return True
        if self._type_store is None:
            self._type_store = self._type_store_source()
        return name in self._type_store or _importable(name)


def _type_store_packages() -> set[str]:
    from launchkit.ros.msgs import packages

    return packages()


def _importable(name: str) -> bool:
    if not name.isidentifier():
        return False
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False
