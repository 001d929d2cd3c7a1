"""The supervisor's side of the child-request socket (the ``ChildHost`` protocol of
:mod:`launchkit.runtime.child_requests`): processes started at a running process's request,
supervised like declared ones, and stopped for their owner."""

from __future__ import annotations

from collections.abc import Callable

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import LaunchkitError
from launchkit.runtime.announcements import Announcements
from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.lifecycle import SendSignal
from launchkit.runtime.node_host import NodeHost
from launchkit.runtime.process import SupervisedProcess, check_program


class RequestError(Exception):
    """A request that cannot be served; its message is the error reply. (Here, not with the
    socket in :mod:`launchkit.runtime.child_requests`: a launch imports that module, and its
    json and socket, only when it starts its first process.)"""


class ChildHostMixin:
    """What :class:`~launchkit.runtime.supervisor.Supervisor` does for processes that ask for
    processes; it uses the supervisor's state and process plumbing declared here."""

    processes: list[SupervisedProcess]
    shutting_down: bool
    clock: Callable[[], float]
    hooks: SupervisorHooks
    _node_host: NodeHost
    _announcements: Announcements

    def log(self, level: str, logger: str, message: str) -> None:
        """A launch line (the supervisor's)."""
        raise NotImplementedError

    def _managed(self, spec: ProcessSpec) -> SupervisedProcess:
        raise NotImplementedError

    def announce(self, logger: str, text: str) -> None:
        """A line for the user (``{"op": "announce"}``), held until the console settles."""
        self._announcements.hold(logger, text, self.clock())

    def _watch(self, process: SupervisedProcess) -> None:
        raise NotImplementedError

    def _send(self, process: SupervisedProcess, effect: SendSignal) -> None:
        raise NotImplementedError

    def owner_of(self, pid: int) -> SupervisedProcess | None:
        """The running process of the launch whose pid (and so session) is ``pid``."""
        return next((p for p in self.processes if p.alive and p.pid == pid), None)

    def owner_of_forked(self, pid: int) -> SupervisedProcess | None:
        """The running process of the launch whose trampoline stands for node ``pid``, forked
        from the launcher's node host (:mod:`launchkit.runtime.node_host`)."""
        trampoline = self._node_host.trampoline_of(pid)
        return None if trampoline is None else self.owner_of(trampoline)

    def start_child(self, spec: ProcessSpec, owner: SupervisedProcess) -> SupervisedProcess:
        """Start ``spec`` at ``owner``'s request; :class:`RequestError` if it cannot start
        (a refused request never stops the launch)."""
        if self.shutting_down:
            raise RequestError("the launch is shutting down")
        try:
            check_program(spec)
        except LaunchkitError as error:
            raise RequestError(error.message) from None
        process = self._managed(spec)
        try:
            process.spawn()
        except OSError as error:
            raise RequestError(f"could not start '{spec.cmd[0]}': {error.strerror}") from None
        process.lifecycle.started(self.clock())
        self.processes.append(process)
        self.log("INFO", process.label, f"started at the request of {owner.label}")
        self._watch(process)
        return process

    def stop_child(self, process: SupervisedProcess) -> None:
        """Stop a process started on request, as a shutdown would, and never respawn it."""
        effect = process.lifecycle.stop(self.clock(), retire=True)
        if effect is not None:
            self.hooks.process_stopping(process)
            self._send(process, effect)
