"""Launch events from what the supervisor sees: an observer that turns process starts, output
lines and exits into ROS's ProcessStarted / ProcessIO / ProcessExited / ExecutionComplete
events in the launch context's queue, then passes them on to the next observer.

The supervisor drains the queue on its loop (:func:`launchkit.description.events.drain_events`),
so the handlers' actions run after the line that says what happened.
"""

from __future__ import annotations

import os
import selectors
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.description.events import (
    ExecutionComplete,
    ProcessExited,
    ProcessIO,
    ProcessStarted,
    Shutdown,
    dispatch,
    drain_events,
)
from launchkit.errors import LaunchkitError
from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.lifecycle import State

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext
    from launchkit.runtime.process import SupervisedProcess


class EventRelay(SupervisorHooks):
    """Emits launch events for the processes the launch file started (not for processes
    started at a child's request, which no action names), and forwards everything to ``inner``."""

    def __init__(self, inner: SupervisorHooks) -> None:
        self.inner = inner
        self.context: LaunchContext | None = None
        self._wakeup: tuple[int, int] | None = None
        self._selector: selectors.BaseSelector | None = None
        self._error: LaunchkitError | None = None

    def _details(self, process: SupervisedProcess) -> dict[str, Any] | None:
        spec = process.spec
        if self.context is None or spec.origin is None:
            return None
        return {
            "action": spec.origin,
            "name": process.label,
            "cmd": spec.cmd,
            "cwd": spec.cwd,
            "env": spec.env,
            "pid": process.pid or 0,
        }

    def attach(self, context: LaunchContext, selector: selectors.BaseSelector) -> LaunchContext:
        """Relay to ``context``; work posted to it from other threads wakes ``selector``."""
        self.context = context
        self._wakeup = os.pipe()
        os.set_blocking(self._wakeup[0], False)
        os.set_blocking(self._wakeup[1], False)
        selector.register(self._wakeup[0], selectors.EVENT_READ, self._woken)
        self._selector = selector
        context.waker = self._wake
        return context

    def _wake(self) -> None:
        if self._wakeup is not None:
            try:
                os.write(self._wakeup[1], b"x")
            except (BlockingIOError, OSError):
                pass  # a wake-up is pending already (or the launch is over)

    def _woken(self) -> None:
        if self._wakeup is not None:
            try:
                while os.read(self._wakeup[0], 4096):
                    pass
            except BlockingIOError:
                pass

    def close(self) -> None:
        """Release the wake-up pipe."""
        if self.context is not None:
            self.context.waker = None
        if self._wakeup is not None:
            if self._selector is not None:
                self._selector.unregister(self._wakeup[0])
            for fd in self._wakeup:
                os.close(fd)
            self._wakeup = None

    def drain(self, fail: Callable[[LaunchkitError], None]) -> None:
        """Run the posted work and the handlers of the queued events; ``fail`` with the error
        that stopped them, if any."""
        if self._error is not None:
            error, self._error = self._error, None
            fail(error)
        if self.context is None:
            return
        try:
            drain_events(self.context)
        except LaunchkitError as error:
            fail(error)

    def _drain_now(self) -> None:
        """Run the handlers at once (a line's handlers before the exit that may follow it);
        an error is reported by the next :meth:`drain`."""
        if self.context is not None:
            try:
                drain_events(self.context)
            except LaunchkitError as error:
                self._error = self._error or error

    def shutting_down(self, reason: str, due_to_sigint: bool) -> LaunchkitError | None:
        """The launch starts shutting down: run the OnShutdown handlers now, before any
        process is signalled (as ROS does); the error that stopped them, if any."""
        if self.context is None:
            return None
        self.context.is_shutdown = True
        try:
            dispatch(self.context, Shutdown(reason=reason, due_to_sigint=due_to_sigint))
        except LaunchkitError as error:
            return error
        return None

    def launch_ready(self) -> None:
        """See :class:`SupervisorHooks`."""
        self.inner.launch_ready()

    def launch_error(self, message: str) -> None:
        """See :class:`SupervisorHooks`."""
        self.inner.launch_error(message)

    def process_started(self, process: SupervisedProcess) -> None:
        """See :class:`SupervisorHooks`; emits ProcessStarted."""
        self.inner.process_started(process)
        details = self._details(process)
        if details is not None and self.context is not None:
            self.context.emit(ProcessStarted(**details))

    def process_output(self, process: SupervisedProcess, stream: str, line: str) -> None:
        """See :class:`SupervisorHooks`; emits ProcessIO when some handler may want it."""
        self.inner.process_output(process, stream, line)
        if self.context is None or not self.context.handlers:
            return
        details = self._details(process)
        if details is not None:
            fd = 2 if stream == "stderr" else 1
            event = ProcessIO(text=(line + "\n").encode(), fd=fd, **details)
            self.context.emit(event)
            self._drain_now()

    def process_stopping(self, process: SupervisedProcess) -> None:
        """See :class:`SupervisorHooks`."""
        self.inner.process_stopping(process)

    def process_exited(self, process: SupervisedProcess, returncode: int) -> None:
        """See :class:`SupervisorHooks`; emits ProcessExited, and ExecutionComplete when the
        process will not be respawned."""
        self.inner.process_exited(process, returncode)
        details = self._details(process)
        if details is None or self.context is None:
            return
        self.context.emit(ProcessExited(returncode=returncode, **details))
        if process.lifecycle.state is not State.BACKOFF:
            self.context.emit(ExecutionComplete(action=process.spec.origin))

    def shutdown(self, reason: str) -> None:
        """See :class:`SupervisorHooks`."""
        self.inner.shutdown(reason)
