"""launchkit: run ROS 2 launch files, and the robot they describe, without a ROS install.

The public API, for programs that drive launchkit the way the ``launchkit`` command does::

    import launchkit

    packages = launchkit.PackageIndex()
    path = launchkit.resolve_launch_file("robot_wheel", "display.launch.xml", packages)
    launchkit.check(path, {"model": "my.urdf"})      # parse and check; raises a UserError
    print(launchkit.describe(path))                   # what would run
    status = launchkit.run(path)                      # run until everything has stopped

Errors are one tree (drawn in :mod:`launchkit.errors`): every user mistake is a
:class:`UserError` with a file:line:col location where it has one. The ROS 2 node API is
:mod:`launchkit.ros`, the pytest plugin :mod:`launchkit.testing`.

The API functions are imported on first use, so ``import launchkit.ros`` in a node process does
not load the launch engine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes
from launchkit.errors import (
    LaunchArgumentError,
    LaunchFileError,
    LaunchkitError,
    Location,
    PackageNotFoundError,
    RuntimeLaunchError,
    UserError,
)

if TYPE_CHECKING:
    from launchkit.api import check, describe, resolve_launch_file, run, show_arguments
    from launchkit.checks import CheckedTree
    from launchkit.packages import PackageIndex
    from launchkit.runtime.hooks import SupervisorHooks

__version__ = "0.1.0"

#: Public name -> the module that defines it (imported when the name is first used).
_LAZY = {
    "CheckedTree": "launchkit.checks",
    "PackageIndex": "launchkit.packages",
    "SupervisorHooks": "launchkit.runtime.hooks",
    "check": "launchkit.api",
    "describe": "launchkit.api",
    "resolve_launch_file": "launchkit.api",
    "run": "launchkit.api",
    "show_arguments": "launchkit.api",
}


__getattr__ = lazy_attributes(__name__, _LAZY, globals())


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


__all__ = [
    "CheckedTree",
    "LaunchArgumentError",
    "LaunchFileError",
    "LaunchkitError",
    "Location",
    "PackageIndex",
    "PackageNotFoundError",
    "RuntimeLaunchError",
    "SupervisorHooks",
    "UserError",
    "__version__",
    "check",
    "describe",
    "resolve_launch_file",
    "run",
    "show_arguments",
]
