"""``find-pkg-share``, ``find-pkg-prefix`` and ``exec-in-pkg``: the package index."""

from __future__ import annotations

import shlex
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call
from launchkit.errors import PackageNotFoundError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class FindPkgShare(Call):
    """Share directory of package PKG."""

    NAME = "find-pkg-share"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "PKG"

    def perform(self, context: LaunchContext) -> str:
        """The directory path, or an error listing where packages were searched."""
        try:
            return str(context.packages.share_dir(self.arg(0, context)))
        except PackageNotFoundError as error:
            raise error.with_location(self.location) if self.location else error from None


class FindPkgPrefix(Call):
    """Install prefix of package PKG."""

    NAME = "find-pkg-prefix"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "PKG"

    def perform(self, context: LaunchContext) -> str:
        """The prefix path, or an error listing where packages were searched."""
        try:
            return str(context.packages.prefix(self.arg(0, context)))
        except PackageNotFoundError as error:
            raise error.with_location(self.location) if self.location else error from None


class ExecInPkg(Call):
    """Path of executable EXE of package PKG.

    For a Python package's executable there is no file to point at: the result is its command
    line (``PYTHON -m MODULE``), which a shell or ``$(command)`` runs as is.
    """

    NAME = "exec-in-pkg"
    MIN_ARGS = 2
    MAX_ARGS = 2
    USAGE = "EXE PKG"

    def perform(self, context: LaunchContext) -> str:
        """The executable's path, or an error naming what is missing."""
        try:
            argv = context.packages.executable(self.arg(1, context), self.arg(0, context))
            if len(argv) == 1:
                return argv[0]
            return shlex.join(argv)
        except PackageNotFoundError as error:
            raise error.with_location(self.location) if self.location else error from None
