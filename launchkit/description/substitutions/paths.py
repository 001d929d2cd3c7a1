"""Substitutions about files: ``find-exec``, ``dirname``, ``filename``, ``file-content``,
``log_dir``."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class FindExec(Call):
    """Absolute path of executable NAME found on the launch's PATH."""

    NAME = "find-exec"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "NAME"

    def perform(self, context: LaunchContext) -> str:
        """The path, or an error naming the executable and the PATH searched."""
        name = self.arg(0, context)
        path = shutil.which(name, path=context.environment.get("PATH"))
        if path is None:
            raise self.fail(f"executable '{name}' not found on the PATH")
        return path


class _ThisFile(Call):
    MIN_ARGS = 0
    MAX_ARGS = 0

    def _file(self, context: LaunchContext) -> Path:
        if context.current_file is None:
            raise self.fail(f"$({self.NAME}) used outside a launch file")
        return context.current_file


class Dirname(_ThisFile):
    """Directory of the launch file this substitution is written in."""

    NAME = "dirname"

    def perform(self, context: LaunchContext) -> str:
        """The absolute directory path."""
        return str(self._file(context).parent)


class Filename(_ThisFile):
    """Absolute path of the launch file this substitution is written in."""

    NAME = "filename"

    def perform(self, context: LaunchContext) -> str:
        """The absolute file path."""
        return str(self._file(context))


class FileContent(Call):
    """The text of file PATH, verbatim."""

    NAME = "file-content"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "PATH"

    def perform(self, context: LaunchContext) -> str:
        """The file's text, or an error naming the file."""
        path = self.arg(0, context)
        try:
            return Path(path).read_text()
        except OSError as error:
            raise self.fail(f"cannot read file '{path}': {error.strerror}") from None


class LogDir(Call):
    """This run's log directory."""

    NAME = "log_dir"
    MIN_ARGS = 0
    MAX_ARGS = 0

    def perform(self, context: LaunchContext) -> str:
        """The directory path (created on first use)."""
        return str(context.log_dir)


class LaunchLogDir(LogDir):
    """Alias ``$(launch_log_dir)``."""

    NAME = "launch_log_dir"
