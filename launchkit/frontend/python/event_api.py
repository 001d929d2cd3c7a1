"""Stand-ins for ``launch``'s event system and ``OpaqueFunction``: ``RegisterEventHandler``
with ``OnProcessStart`` / ``OnProcessExit`` / ``OnProcessIO`` / ``OnExecutionComplete`` /
``OnShutdown``, ``EmitEvent``, the events and their matchers.

A handler's reaction is a list of actions, or a function of the launch file called with the
event (and, but for OnProcessIO, the context) that returns actions; the function runs with the
stand-in modules installed, and its exception is reported with its file and line.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from launchkit.description.actions.base import Action
from launchkit.description.actions.event_actions import (
    EmitEvent as EmitEventAction,
)
from launchkit.description.actions.event_actions import (
    RegisterEventHandler as RegisterAction,
)
from launchkit.description.actions.event_actions import (
    UnregisterEventHandler as UnregisterAction,
)
from launchkit.description.conditions import Condition
from launchkit.description.events import (
    Event,
    EventHandler,
    ExecutionComplete,
    ProcessExited,
    ProcessIO,
    ProcessStarted,
    Shutdown,
    action_matcher,
)
from launchkit.description.launch_context import LaunchContext, Visitable
from launchkit.description.substitutions.base import literal
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.python.launch_api import flatten
from launchkit.frontend.python.values import (
    LaunchContextView,
    call_user,
    current_modules,
    function_name,
    here,
)


def describe_action(action: object) -> str:
    """A short name for an action in ``--print`` (its process name when it has one)."""
    for attribute in ("node_name", "exec"):
        value = getattr(action, attribute, None)
        if isinstance(value, tuple) and literal(value):
            return str(literal(value))
    options = getattr(action, "options", None)
    name = getattr(options, "name", None)
    if isinstance(name, tuple) and literal(name):
        return str(literal(name))
    words = getattr(action, "words", None)
    if words and literal(words[0]):
        return str(literal(words[0]))
    return type(action).__name__


class _Reaction(EventHandler):
    """A handler whose reaction is a list of actions or a function of the launch file."""

    #: Whether the function takes the context too (all but OnProcessIO's).
    WITH_CONTEXT = True

    def __init__(
        self,
        matcher: Callable[[Event], bool],
        reaction: Any,
        what: str,
        handle_once: bool = False,
    ) -> None:
        if callable(reaction) and not isinstance(reaction, Action):
            entities: list[Action] = [CallOnEvent(reaction, what, self.WITH_CONTEXT)]
        else:
            entities = flatten(reaction, what)
        super().__init__(matcher=matcher, entities=entities, handle_once=handle_once)
        self.what = what
        self.location = here()


class _OnAction(_Reaction):
    """OnActionEventBase: events of one kind, from one action (or a predicate, or any)."""

    EVENT: type[Event] = Event
    REACTION = ""

    def __init__(
        self,
        *,
        target_action: Any = None,
        handle_once: bool = False,
        **reaction: Any,
    ) -> None:
        if set(reaction) != {self.REACTION}:
            given = ", ".join(sorted(reaction)) or "nothing"
            raise LaunchFileError(
                f"{type(self).__name__} got {given}",
                here(),
                expected=f"target_action=..., {self.REACTION}=[actions] or a function",
            )
        self.target = target_action
        matcher = action_matcher(self.EVENT, target_action)
        super().__init__(matcher, reaction[self.REACTION], type(self).__name__, handle_once)

    def describe(self) -> str:
        """``OnProcessExit(target_action=NAME)``."""
        target = self.target
        if target is None:
            return f"{type(self).__name__}(any process)"
        name = describe_action(target) if isinstance(target, Action) else "a matcher"
        return f"{type(self).__name__}(target_action={name})"


class OnProcessStart(_OnAction):
    """``launch.event_handlers.OnProcessStart(target_action=..., on_start=...)``."""

    EVENT = ProcessStarted
    REACTION = "on_start"


class OnProcessExit(_OnAction):
    """``launch.event_handlers.OnProcessExit(target_action=..., on_exit=...)``."""

    EVENT = ProcessExited
    REACTION = "on_exit"


class OnExecutionComplete(_OnAction):
    """``launch.event_handlers.OnExecutionComplete(target_action=..., on_completion=...)``."""

    EVENT = ExecutionComplete
    REACTION = "on_completion"


class OnProcessIO(_Reaction):
    """``launch.event_handlers.OnProcessIO``: ``on_stdout`` / ``on_stderr`` are functions of
    the ProcessIO event (one line of output, as bytes, in ``event.text``)."""

    WITH_CONTEXT = False

    def __init__(
        self,
        *,
        target_action: Any = None,
        on_stdin: Callable[[ProcessIO], Any] | None = None,
        on_stdout: Callable[[ProcessIO], Any] | None = None,
        on_stderr: Callable[[ProcessIO], Any] | None = None,
        handle_once: bool = False,
    ) -> None:
        del on_stdin  # launchkit gives children no stdin events
        self.target = target_action

        def route(event: ProcessIO) -> Any:
            reaction = on_stdout if event.from_stdout else on_stderr
            return None if reaction is None else reaction(event)

        route.__qualname__ = "OnProcessIO"
        super().__init__(action_matcher(ProcessIO, target_action), route, "OnProcessIO")
        self.handle_once = handle_once
        self.functions = [f for f in (on_stdout, on_stderr) if f is not None]

    def children(self) -> Sequence[Visitable]:
        """The calls of the launch file's functions (what ``--print`` shows of them)."""
        return [CallOnEvent(function, "OnProcessIO", False) for function in self.functions]

    describe = _OnAction.describe


class OnShutdown(_Reaction):
    """``launch.event_handlers.OnShutdown(on_shutdown=...)``: runs before processes are
    signalled; ``event.reason`` says why."""

    def __init__(self, *, on_shutdown: Any, handle_once: bool = False) -> None:
        super().__init__(
            lambda event: isinstance(event, Shutdown), on_shutdown, "OnShutdown", handle_once
        )


class GenericEventHandler(_Reaction):
    """``launch.EventHandler(matcher=..., entities=...)``."""

    def __init__(
        self, *, matcher: Callable[[Event], bool], entities: Any = None, handle_once: bool = False
    ) -> None:
        super().__init__(matcher, entities or [], "EventHandler", handle_once)


class RegisterEventHandler(RegisterAction):
    """``launch.actions.RegisterEventHandler(event_handler=...)``."""

    def __init__(self, event_handler: EventHandler, *, condition: Condition | None = None):
        if not isinstance(event_handler, EventHandler):
            raise LaunchFileError(
                f"RegisterEventHandler got a {type(event_handler).__name__}",
                here(),
                expected="an event handler such as OnProcessExit(...)",
            )
        super().__init__(event_handler, here(), condition)


class UnregisterEventHandler(UnregisterAction):
    """``launch.actions.UnregisterEventHandler(event_handler=...)``."""

    def __init__(self, event_handler: EventHandler, *, condition: Condition | None = None):
        super().__init__(event_handler, here(), condition)


class EmitEvent(EmitEventAction):
    """``launch.actions.EmitEvent(event=...)``."""

    def __init__(self, *, event: Event, condition: Condition | None = None) -> None:
        if not isinstance(event, Event):
            raise LaunchFileError(
                f"EmitEvent got a {type(event).__name__}",
                here(),
                expected="an event such as launch.events.Shutdown(reason='...')",
            )
        super().__init__(event, here(), condition)


class OpaqueFunction(Action):
    """``launch.actions.OpaqueFunction(function=f, args=[...], kwargs={...})``: calls
    ``f(context, *args, **kwargs)`` when reached and runs the actions it returns there."""

    def __init__(
        self,
        *,
        function: Callable[..., Any],
        args: Sequence[Any] | None = None,
        kwargs: dict[str, Any] | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(here(), condition)
        if not callable(function):
            raise LaunchFileError(
                f"OpaqueFunction got a {type(function).__name__}",
                self.location,
                expected="function=a function taking the context",
            )
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})
        self._modules = current_modules()

    def execute(self, context: LaunchContext) -> None:
        """Call the function and run what it returns (``--print`` showing an event handler's
        actions only says it would)."""
        name = function_name(self.function)
        if context.instead_of_calling is not None:
            context.instead_of_calling(f"{name} (OpaqueFunction)", self.location)
            return
        view = LaunchContextView(context)
        result = call_user(
            self.function, "OpaqueFunction", self._modules, view, *self.args, **self.kwargs
        )
        for action in flatten(result, f"OpaqueFunction {name}()"):
            action.visit(context)


class CallOnEvent(Action):
    """A function of the launch file that reacts to an event (an event handler's, or an
    ExecuteProcess's ``on_exit``): called with the event (and the context) when its handler
    runs, then what it returns runs. ``--print`` and ``check`` only say they would call it
    (ROS calls it only on the event)."""

    def __init__(self, function: Callable[..., Any], what: str, with_context: bool = True):
        super().__init__(here())
        self.function = function
        self.what = what
        self.with_context = with_context
        self._modules = current_modules()

    def execute(self, context: LaunchContext) -> None:
        """Call the function with the event being handled and run what it returns."""
        name = function_name(self.function)
        if context.instead_of_calling is not None:
            context.instead_of_calling(name, where(self.function))
            return
        event = context.locals.get("event")
        args = (event, LaunchContextView(context)) if self.with_context else (event,)
        result = call_user(self.function, self.what, self._modules, *args)
        for action in flatten(result, f"{self.what} {name}()"):
            action.visit(context)


def where(function: Callable[..., Any]) -> Location | None:
    """Where ``function`` is defined."""
    code = getattr(function, "__code__", None)
    return None if code is None else Location(code.co_filename, code.co_firstlineno)


def matches_action(target_action: Any) -> Callable[[Any], bool]:
    """``launch.events.matches_action``."""
    return lambda action: action is target_action


def _matches_detail(key: str, test: Callable[[Any], bool]) -> Callable[[Any], bool]:
    def matcher(action: Any) -> bool:
        details = getattr(action, "process_details", None)
        return details is not None and test(details[key])

    return matcher


def matches_pid(pid: int) -> Callable[[Any], bool]:
    """``launch.events.process.matches_pid``."""
    return _matches_detail("pid", lambda value: value == pid)


def matches_name(name: str) -> Callable[[Any], bool]:
    """``launch.events.process.matches_name`` (the process's name, e.g. ``talker-1``)."""
    return _matches_detail("name", lambda value: value == name)


def matches_executable(executable: str) -> Callable[[Any], bool]:
    """``launch.events.process.matches_executable``."""
    return _matches_detail("cmd", lambda value: bool(value) and value[0].endswith(executable))
