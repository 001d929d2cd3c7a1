"""``<timer>``: run actions after a delay, in the scope the timer was reached in."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action, typed_float
from launchkit.description.substitutions.base import Value
from launchkit.errors import Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class Timer(Action):
    """After PERIOD seconds run the children; the scope is captured when the timer is reached
    (so a timer in a scoped group keeps the group's configurations, unlike ROS 2 Jazzy)."""

    TAG = "timer"
    COMPLETES_LATER = True

    def __init__(
        self,
        period: Value,
        actions: Sequence[Action],
        cancel_on_shutdown: bool = True,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.period = period
        self.actions = list(actions)
        self.cancel_on_shutdown = cancel_on_shutdown

    def children(self) -> Sequence[Action]:
        """The delayed actions."""
        return self.actions

    def execute(self, context: LaunchContext) -> None:
        """Schedule the children."""
        period = typed_float(self.period, context, "timer period", self.location)
        if period < 0:
            raise RuntimeLaunchError(
                f"timer period is {period}", self.location, expected="a period >= 0"
            )
        context.runner.schedule_timer(period, self, context.snapshot())
