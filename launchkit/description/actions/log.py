"""``<log>`` and ``<shutdown>``."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext

LEVELS = ("DEBUG", "INFO", "WARNING", "ERROR")


class Log(Action):
    """Print MESSAGE as ``[INFO] [launch.user]: MESSAGE`` (``level`` is a launchkit extra)."""

    TAG = "log"

    def __init__(
        self,
        message: Value,
        level: str = "INFO",
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.message = message
        self.level = level

    def execute(self, context: LaunchContext) -> None:
        """Print it."""
        context.log(self.level, perform(self.message, context), logger="launch.user")


class Shutdown(Action):
    """Shut the whole launch down, giving REASON."""

    TAG = "shutdown"

    def __init__(
        self,
        reason: Value = (),
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.reason = reason

    def execute(self, context: LaunchContext) -> None:
        """Ask the runner to shut down."""
        context.runner.request_shutdown(perform(self.reason, context) or "<shutdown> reached")
