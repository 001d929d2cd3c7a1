"""The ``context`` a launch file's own functions receive (OpaqueFunction, event handler
callbacks, ``Substitution.perform``): the part of ROS's ``launch.LaunchContext`` that launch
files use, over launchkit's :class:`~launchkit.description.launch_context.LaunchContext`."""

from __future__ import annotations

import types
from collections.abc import Iterable
from typing import Any

from launchkit.description.actions.event_actions import EmitEvent
from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions.base import perform
from launchkit.errors import LaunchFileError
from launchkit.frontend.python.values import here, to_value


class LaunchContextView:
    """ROS's LaunchContext API for user code: configurations, environment, locals, performing
    substitutions, registering handlers and emitting events."""

    def __init__(self, context: LaunchContext) -> None:
        self.real = context

    @property
    def launch_configurations(self) -> dict[str, str]:
        """The launch configurations of the current scope (a live dict)."""
        return self.real.configurations

    @property
    def environment(self) -> dict[str, str]:
        """The environment processes started now inherit (a live dict)."""
        return self.real.environment

    def get_locals_as_dict(self) -> dict[str, Any]:
        """The locals: ``event`` in a handler, the current launch file's path and folder."""
        values = dict(self.real.locals)
        current = self.real.current_file
        if current is not None:
            values.setdefault("current_launch_file_path", str(current))
            values.setdefault("current_launch_file_directory", str(current.parent))
        return values

    @property
    def locals(self) -> types.SimpleNamespace:
        """The locals as attributes (``context.locals.event``)."""
        return types.SimpleNamespace(**self.get_locals_as_dict())

    def extend_locals(self, new_locals: dict[str, Any]) -> None:
        """Add locals (for the rest of the current handler or function)."""
        self.real.locals.update(new_locals)

    @property
    def is_shutdown(self) -> bool:
        """Whether the launch is shutting down."""
        return self.real.is_shutdown

    def perform_substitution(self, substitution: Any) -> str:
        """The text of a substitution (or of a list of them) now."""
        return perform(to_value(substitution), self.real)

    def register_event_handler(self, event_handler: Any, append: bool = False) -> None:
        """Register a handler (newest first unless ``append``)."""
        self.real.register_handler(event_handler)
        if append:
            self.real.handlers.remove(event_handler)
            self.real.handlers.append(event_handler)

    def unregister_event_handler(self, event_handler: Any) -> None:
        """Unregister a handler."""
        if event_handler in self.real.handlers:
            self.real.handlers.remove(event_handler)

    def emit_event_sync(self, event: Any) -> None:
        """Emit an event, as ``EmitEvent(event=...)`` would."""
        EmitEvent(event, here()).execute(self.real)

    emit_event = emit_event_sync

    def __getattr__(self, name: str) -> Any:
        raise LaunchFileError(
            f"LaunchContext.{name} is not provided by launchkit",
            here(),
            expected="launch_configurations, environment, locals, perform_substitution, "
            "register_event_handler, emit_event",
        )


def perform_substitutions(context: Any, substitutions: Iterable[Any]) -> str:
    """``launch.utilities.perform_substitutions``."""
    return perform(to_value(list(substitutions)), getattr(context, "real", context))
