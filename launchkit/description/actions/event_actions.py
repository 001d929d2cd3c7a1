"""Actions of the event system: register or unregister a handler, emit an event."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.events import EventHandler, Shutdown, ShutdownProcess, SignalProcess
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


class RegisterEventHandler(Action):
    """Add ``handler`` to the launch: from now on it reacts to the events it matches."""

    def __init__(
        self,
        handler: EventHandler,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.handler = handler

    def children(self) -> Sequence[Action]:
        """The handler's actions (those known before any event)."""
        return [a for a in self.handler.children() if isinstance(a, Action)]

    def execute(self, context: LaunchContext) -> None:
        """Register the handler (its actions will run in the current scope)."""
        context.register_handler(self.handler)


class UnregisterEventHandler(Action):
    """Remove ``handler`` (a no-op when it is not registered)."""

    def __init__(
        self,
        handler: EventHandler,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.handler = handler

    def execute(self, context: LaunchContext) -> None:
        """Unregister it."""
        if self.handler in context.handlers:
            context.handlers.remove(self.handler)


class EmitEvent(Action):
    """Emit ``event``: a Shutdown shuts the launch down, ShutdownProcess / SignalProcess stop
    or signal processes, any other event goes to the handlers."""

    def __init__(
        self,
        event: object,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.event = event

    def execute(self, context: LaunchContext) -> None:
        """Emit it."""
        event = self.event
        if isinstance(event, Shutdown):
            context.runner.request_shutdown(event.reason)
        elif isinstance(event, ShutdownProcess):
            context.runner.stop_processes(event.process_matcher, None)
        elif isinstance(event, SignalProcess):
            context.runner.stop_processes(event.process_matcher, event.signal_number)
        else:
            context.emit(event)
