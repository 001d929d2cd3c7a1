"""A runtime that runs nothing: it records what a launch would start, for ``--print``."""

from __future__ import annotations

import shlex
import signal
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import Location, printable

if TYPE_CHECKING:
    from launchkit.description.launch_context import (
        DelayedActions,
        Handler,
        LaunchContext,
        Snapshot,
        Visitable,
    )


@dataclass
class Recorded:
    """One thing the launch would do: a process, a timer or an event handler (with what it
    would do), a shutdown, a log line, or a call of the launch file's own code (on an event)."""

    kind: str
    delay: float = 0.0
    spec: ProcessSpec | None = None
    text: str = ""
    inner: list[Recorded] = field(default_factory=list)


class _Placeholder:
    """What an event handler's ``LocalSubstitution('event.x')`` shows in ``--print``."""

    def __init__(self, path: str) -> None:
        self._path = path

    def __getattr__(self, name: str) -> _Placeholder:
        return _Placeholder(f"{self._path}.{name}")

    def __str__(self) -> str:
        return f"<{self._path}>"


class Recorder:
    """The :class:`Runner` for ``--print``: timers and event handlers' actions are evaluated
    at once, in their scope (an event's attributes show as ``<event.name>``)."""

    def __init__(self) -> None:
        self._context: LaunchContext | None = None
        self.items: list[Recorded] = []
        self._target = self.items
        self._expanding: list[object] = []

    @property
    def context(self) -> LaunchContext | None:
        """The context being recorded."""
        return self._context

    @context.setter
    def context(self, context: LaunchContext | None) -> None:
        self._context = context
        if context is not None:
            context.on_register = self.handler_registered

    def handler_registered(self, handler: Handler) -> None:
        """Record the handler and the actions it would run (those known without an event);
        launchkit's own handlers are not shown."""
        if getattr(handler, "internal", False):
            return
        describe: Callable[[], str] | None = getattr(handler, "describe", None)
        item = Recorded("handler", text=describe() if describe else type(handler).__name__)
        self._target.append(item)
        children: Sequence[Visitable] = getattr(handler, "children", list)()
        if handler in self._expanding or self.context is None:
            return
        outer, self._target = self._target, item.inner
        self._expanding.append(handler)
        context = self.context
        calling, context.instead_of_calling = context.instead_of_calling, self.would_call
        try:
            assert handler.snapshot is not None
            with context.restored(handler.snapshot), context.local("event", _Placeholder("event")):
                for action in children:
                    action.visit(context)
        finally:
            context.instead_of_calling = calling
            self._expanding.pop()
            self._target = outer

    def would_call(self, what: str, location: Location | None) -> None:
        """Record the launch file's code an event handler would run (never run here: ROS runs
        it only on the event)."""
        self._target.append(Recorded("call", text=what + (f"  ({location})" if location else "")))

    def stop_processes(self, matcher: Callable[[object], bool], signum: int | None) -> None:
        """Record the stop (which processes it reaches is known only while running)."""
        what = "stop" if signum is None else f"send {signal.Signals(signum).name} to"
        self._target.append(Recorded("log", text=f"{what} the matching processes"))

    def start_process(self, spec: ProcessSpec) -> None:
        """Record the process."""
        self._target.append(Recorded("process", spec=spec))

    def schedule_timer(self, period: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Record the timer and what it would do when it fires."""
        item = Recorded("timer", delay=period)
        self._target.append(item)
        outer, self._target = self._target, item.inner
        try:
            assert self.context is not None
            with self.context.restored(snapshot):
                for action in timer.actions:
                    action.visit(self.context)
        finally:
            self._target = outer

    def request_shutdown(self, reason: str) -> None:
        """Record the shutdown."""
        self._target.append(Recorded("shutdown", text=reason))

    def log(self, level: str, logger: str, message: str) -> None:
        """Record the log line."""
        self._target.append(Recorded("log", text=f"[{level}] [{logger}]: {message}"))


def count(items: list[Recorded]) -> tuple[int, int]:
    """(processes, timers) the recorded launch would start, timers' own included."""
    processes = timers = 0
    for item in items:
        if item.kind == "process":
            processes += 1
        elif item.kind == "timer":
            inner = count(item.inner)
            processes, timers = processes + inner[0], timers + 1 + inner[1]
    return processes, timers


def render(items: list[Recorded], indent: str = "") -> str:
    """The recorded launch as readable text."""
    lines: list[str] = []

    def add(line: str) -> None:  # what a file wrote, escaped: it cannot forge a line
        lines.append(printable(line))

    for item in items:
        if item.kind == "process" and item.spec is not None:
            spec = item.spec
            kind = "node" if spec.is_node else "process"
            add(f"{indent}{kind} {spec.name}" + (f"  ({spec.location})" if spec.location else ""))
            if spec.machine:
                add(f"{indent}  machine: {spec.machine} (run by its launchkit agent)")
            add(f"{indent}  cmd: {shlex.join(spec.cmd)}")
            add(f"{indent}  cwd: {spec.cwd or '(launch directory)'}")
            add(f"{indent}  output: {spec.output}")
            for name, value in sorted(spec.env_changes.items()):
                change = "(unset)" if value is None else value
                add(f"{indent}  env: {name}={change}")
            if spec.respawn:
                retries = (
                    "forever"
                    if spec.respawn_max_retries < 0
                    else f"{spec.respawn_max_retries} times"
                )
                add(f"{indent}  respawn: after {spec.respawn_delay:g} s, {retries}")
            if spec.on_exit_shutdown:
                add(f"{indent}  on_exit: shutdown")
            for path, text in spec.files.items():
                add(f"{indent}  file {path}:")
                for line in text.splitlines():
                    add(f"{indent}    {line}")
        elif item.kind == "timer":
            add(f"{indent}timer after {item.delay:g} s:")
            lines.append(render(item.inner, indent + "  ") or f"{indent}  (nothing)")
        elif item.kind == "handler":
            add(f"{indent}event handler {item.text}:")
            lines.append(render(item.inner, indent + "  ") or f"{indent}  (nothing)")
        elif item.kind == "shutdown":
            add(f"{indent}shutdown: {item.text}")
        elif item.kind == "call":
            add(f"{indent}calls {item.text}")
        else:
            add(f"{indent}{item.text}")
    return "\n".join(line for line in lines if line)
