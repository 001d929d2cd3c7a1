"""``<include>``: run another launch file in the caller's scope (not scoped, as in ROS)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import LaunchFileError, LaunchkitError, Location, RuntimeLaunchError
from launchkit.packages import exists, is_file

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


@dataclass(frozen=True)
class IncludeArg:
    """``<arg name value/>`` inside an include."""

    name: str
    value: Value


class Include(Action):
    """Load FILE, set its ``<arg>`` children as configurations, and run its actions.

    ``syntax`` is None to read FILE by its suffix, ``"python"`` or ``"frontend"`` (XML or YAML)
    when a Python launch file's description source class says which.
    """

    TAG = "include"

    def __init__(
        self,
        file: Value,
        args: Sequence[IncludeArg] = (),
        location: Location | None = None,
        condition: Condition | None = None,
        *,
        syntax: str | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.file = file
        self.args = list(args)
        self.syntax = syntax

    def resolve(self, context: LaunchContext) -> Path:
        """The included file: FILE as given (relative to the CWD, as ROS), else relative to
        the including file's directory."""
        text = perform(self.file, context)
        path = Path(text).expanduser()
        if not path.is_absolute() and not exists(path) and context.current_file is not None:
            beside = context.current_file.parent / path
            if exists(beside):
                path = beside
        if not is_file(path):
            raise RuntimeLaunchError(
                f"included launch file '{text}' does not exist",
                self.location,
                expected="a path to a launch file",
            )
        return path.resolve()

    def execute(self, context: LaunchContext) -> None:
        """Include the file in the current scope; an error inside it names this include."""
        path = self.resolve(context)
        if path in context.open_files:
            again = "itself" if path == context.current_file else f"'{path.name}' again"
            raise LaunchFileError(
                f"include cycle: '{context.current_file and context.current_file.name}' "
                f"includes {again} while it is being included",
                self.location or Location(str(path)),
                expected="includes that never lead back to a file that includes them",
            )
        try:
            description = context.loader(path, self.location, self.syntax)
        except LaunchkitError as error:
            self._link(error)
            raise
        values = {arg.name: perform(arg.value, context) for arg in self.args}
        context.configurations.update(values)
        for required in description.required_arguments():
            if required.name not in context.configurations:
                raise required.missing_error().with_location(self.location or Location(str(path)))
        with context.in_file(path):
            try:
                for action in description.actions:
                    action.visit(context)
            except LaunchkitError as error:
                self._link(error)
                raise

    def _link(self, error: LaunchkitError) -> None:
        if self.location is not None:
            error.included_from(self.location)
