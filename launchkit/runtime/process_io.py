"""The supervised processes' side of the supervisor's selector: output and exits.

Each line a child writes goes to the screen and logs (:class:`~launchkit.runtime.output.Output`)
and to the launch's observers as soon as it is read; a child's exit is seen through its pidfd
(or by polling where the kernel has none), and its remaining output is read before the exit is
reported, so lines stay in the order things happened.

Each turn of the loop reads at most :data:`~launchkit.runtime.process.READ_CHUNK` bytes of a
stream, so a child flooding its output (``yes``) shares the loop with everything else: signals,
other children, timers. When a child exits, up to :data:`DRAIN_LIMIT` more bytes are read at
once (what its pipe holds); anything a leftover grandchild keeps writing follows as it comes.
"""

from __future__ import annotations

import selectors
from collections.abc import Callable, Sequence

from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.output import Output
from launchkit.runtime.process import READ_CHUNK, SupervisedProcess

POLL_INTERVAL = 0.05  # seconds between looks at children without a pidfd
DRAIN_LIMIT = 1024 * 1024  # bytes read at once after an exit (a pipe holds 64 KiB by default)


class ProcessIO:
    """Registers processes' streams and exit notifications with ``selector``; ``on_exit`` is
    called on the loop when a process may have exited."""

    def __init__(
        self,
        selector: selectors.BaseSelector,
        output: Output,
        hooks: SupervisorHooks,
        on_exit: Callable[[SupervisedProcess], None],
    ) -> None:
        self._selector = selector
        self._output = output
        self._hooks = hooks
        self._on_exit = on_exit
        self.needs_polling = False  # some process has no pidfd: the loop polls them

    def watch(self, process: SupervisedProcess) -> None:
        """Follow a new incarnation's output and exit."""
        registered = self._selector.get_map()
        for fd in process.streams:
            if fd not in registered:  # an earlier incarnation's stream is registered already
                self._selector.register(fd, selectors.EVENT_READ, _bind(self.read, process, fd))
        if process.pidfd is not None:
            self._selector.register(
                process.pidfd, selectors.EVENT_READ, _bind(self._on_exit, process)
            )
        else:
            self.needs_polling = True

    def read(self, process: SupervisedProcess, fd: int, limit: int = READ_CHUNK) -> None:
        """Pass on what ``process`` wrote on ``fd`` (at most ``limit`` bytes of it); stop
        following the stream at its end."""
        lines, eof = process.read(fd, limit)
        kind = process.streams[fd].kind
        self._output.child_lines(process.label, process.index, lines, process.spec.output, kind)
        for line in lines:
            self._hooks.process_output(process, kind, line)
        if eof:
            self._selector.unregister(fd)
            process.close_stream(fd)

    def exited(self, process: SupervisedProcess) -> None:
        """``process`` exited: stop waiting for its exit and pass on the rest of its output."""
        if process.pidfd is not None:
            self._selector.unregister(process.pidfd)
            process.close_pidfd()
        for fd in list(process.streams):
            self.read(process, fd, DRAIN_LIMIT)

    def poll(self, processes: Sequence[SupervisedProcess]) -> None:
        """Check the running processes that have no pidfd for an exit."""
        if not self.needs_polling:
            return
        for process in list(processes):
            if process.alive and process.pidfd is None and process.poll() is not None:
                self._on_exit(process)


def _bind(function: Callable[..., None], *args: object) -> Callable[[], None]:
    return lambda: function(*args)
