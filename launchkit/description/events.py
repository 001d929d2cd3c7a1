"""Launch events and the handlers that react to them (ROS 2 launch's event system).

Whoever runs a launch emits events into the context's queue (a process started, wrote a line,
exited; an action completed; the launch is shutting down) and drains the queue with
:func:`drain_events` at safe points (after the first pass, after each turn of its loop). Each
event goes to every registered handler that matches it, newest first as in ROS; a handler's
actions run in the scope that was current when the handler was registered, with the event
available to ``LocalSubstitution('event.…')`` as the local ``event``.

The event classes carry ROS's attribute names (``returncode``, ``process_name``, ``text``,
``reason`` ...), so the Python frontend hands them to user callbacks as they are.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from contextlib import nullcontext
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext, Snapshot, Visitable


class Event:
    """Base of every launch event; ``name`` is the event type's ROS name."""

    name = "launch.events.Event"


class ProcessEvent(Event):
    """Something happened to a process started by ``action`` (ROS's RunningProcessEvent)."""

    name = "launch.events.process.RunningProcessEvent"

    def __init__(
        self,
        *,
        action: object,
        name: str,
        cmd: list[str],
        cwd: str | None,
        env: dict[str, str] | None,
        pid: int,
    ) -> None:
        self.action = action
        self.process_name = name
        self.cmd = cmd
        self.cwd = cwd
        self.env = env
        self.pid = pid

    @property
    def execute_process_action(self) -> object:
        """The action that started the process (ROS's alias of ``action``)."""
        return self.action

    def details(self) -> dict[str, Any]:
        """What ROS keeps as the action's ``process_details``."""
        return {"name": self.process_name, "cmd": self.cmd, "cwd": self.cwd, "pid": self.pid}


class ProcessStarted(ProcessEvent):
    """The process runs (first start or respawn)."""

    name = "launch.events.process.ProcessStarted"


class ProcessExited(ProcessEvent):
    """The process exited with ``returncode`` (negative: killed by that signal)."""

    name = "launch.events.process.ProcessExited"

    def __init__(self, *, returncode: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.returncode = returncode


class ProcessIO(ProcessEvent):
    """The process wrote ``text`` (one line, with its newline) on ``fd`` (1 stdout, 2 stderr)."""

    name = "launch.events.process.ProcessIO"

    def __init__(self, *, text: bytes, fd: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.text = text
        self.fd = fd
        self.from_stdin = fd == 0
        self.from_stdout = fd == 1
        self.from_stderr = fd == 2


class ExecutionComplete(Event):
    """``action`` finished: at once for most actions, at the final exit for a process, when
    it fired for a timer."""

    name = "launch.events.ExecutionComplete"

    def __init__(self, *, action: object) -> None:
        self.action = action


class Shutdown(Event):
    """The launch is shutting down (``EmitEvent(event=Shutdown(reason=...))`` asks for it)."""

    name = "launch.events.Shutdown"

    def __init__(self, *, reason: str = "reason not given", due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint


class ProcessTargetedEvent(Event):
    """An event aimed at the running processes whose action ``process_matcher`` accepts."""

    name = "launch.events.process.ProcessTargetedEvent"

    def __init__(self, *, process_matcher: Callable[[object], bool]) -> None:
        self.process_matcher = process_matcher


class ShutdownProcess(ProcessTargetedEvent):
    """Stop the matching processes as a shutdown would (SIGINT, then escalation), no respawn."""

    name = "launch.events.process.ShutdownProcess"


class SignalProcess(ProcessTargetedEvent):
    """Send ``signal_number`` to the matching processes."""

    name = "launch.events.process.SignalProcess"

    def __init__(self, *, signal_number: int, process_matcher: Callable[[object], bool]) -> None:
        super().__init__(process_matcher=process_matcher)
        self.signal_number = int(signal_number)


class EventHandler:
    """Reacts to the events ``matcher`` accepts with ``entities`` (or what ``handle`` returns).

    ``snapshot`` is the scope the handler was registered in (set by RegisterEventHandler);
    ``handle_once`` unregisters it after its first event.
    """

    def __init__(
        self,
        *,
        matcher: Callable[[Event], bool],
        entities: Sequence[Visitable] = (),
        handle_once: bool = False,
        description: str | None = None,
    ) -> None:
        self.matcher = matcher
        self.entities = list(entities)
        self.handle_once = handle_once
        self.description = description
        self.snapshot: Snapshot | None = None
        #: Registered by launchkit itself (``--print`` does not show it).
        self.internal = False

    def matches(self, event: object) -> bool:
        """Whether this handler reacts to ``event``."""
        return isinstance(event, Event) and self.matcher(event)

    def handle(self, event: object, context: LaunchContext) -> Sequence[Visitable]:
        """The actions to run for ``event``."""
        return self.entities

    def children(self) -> Sequence[Visitable]:
        """The actions known before any event (for walking the tree without running it)."""
        return self.entities

    def describe(self) -> str:
        """What the handler waits for (``--print``)."""
        return self.description or type(self).__name__


def action_matcher(event_type: type[Event], target: object | None) -> Callable[[Event], bool]:
    """ROS's OnActionEventBase matching: events of ``event_type`` whose action is ``target``
    (an action, a predicate on the action, or None for any)."""

    def matches(event: Event) -> bool:
        if not isinstance(event, event_type):
            return False
        action = getattr(event, "action", None)
        if target is None:
            return True
        if callable(target):
            return bool(target(action))
        return action is target

    return matches


def dispatch(context: LaunchContext, event: object) -> None:
    """Give ``event`` to every matching handler now, newest handler first."""
    if isinstance(event, ProcessStarted) and event.action is not None:
        try:
            event.action.process_details = event.details()  # type: ignore[attr-defined]
        except AttributeError:
            pass
    for handler in tuple(context.handlers):
        if handler not in context.handlers or not handler.matches(event):
            continue
        if handler.handle_once:
            context.handlers.remove(handler)
        scope = context.restored(handler.snapshot) if handler.snapshot else nullcontext()
        with scope, context.local("event", event):
            for action in handler.handle(event, context):
                action.visit(context)


def drain_events(context: LaunchContext) -> None:
    """Dispatch every queued event, and those their handlers emit, in order (not re-entrant:
    a drain started from inside a handler leaves the work to the outer one)."""
    if context.draining:
        return
    context.draining = True
    try:
        while context.posted or context.event_queue:
            while context.posted:
                context.posted.popleft()()
            if context.event_queue:
                dispatch(context, context.event_queue.popleft())
    finally:
        context.draining = False
