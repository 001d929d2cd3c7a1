"""The supervisor: one loop that starts processes, reads their output, fires timers, handles
signals and shuts everything down, in order.

Everything happens on the main thread in :meth:`Supervisor.run`. Child exits are seen through
pidfds, output through non-blocking pipes, signals through a wakeup fd, all in one selector, so
a lifecycle line is printed only after the child's remaining output: lines stay chronological.

Each process's states, respawns and stop escalation are decided by its
:class:`~launchkit.runtime.lifecycle.Lifecycle`; the supervisor carries out what it decides and
says so on screen. Processes come from an injectable factory and time from an injectable clock,
so the loop is unit-tested without real processes (``tests/engine/test_supervisor_loop.py``).

Evaluating actions (the first pass, a timer) may block, in a ``$(command)`` say; there a signal
interrupts the evaluation (:meth:`SignalPipe.interrupting`), and is then handled as always.
Processes of the launch may also ask the supervisor, over the child-request socket it serves on
the same loop (:mod:`launchkit.runtime.child_requests`), to start processes for them; those are
supervised exactly like declared ones and stopped when their owner's connection closes.
"""

from __future__ import annotations

import selectors
import signal
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from launchkit.description.events import ExecutionComplete
from launchkit.description.process_spec import ProcessSpec
from launchkit.envvars import RUN_TMPDIR
from launchkit.errors import LaunchkitError
from launchkit.ros.face import child_environment
from launchkit.runtime.announcements import Announcements
from launchkit.runtime.child_requests import ChildRequests, RequestError
from launchkit.runtime.cleanup import LaunchCleanup
from launchkit.runtime.containment import SWEEP_PERIOD
from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.launch_events import EventRelay
from launchkit.runtime.lifecycle import Respawn, SendSignal, State
from launchkit.runtime.output import Output
from launchkit.runtime.process import (
    ManagedProcess,
    ProcessFactory,
    SupervisedProcess,
    by_machine,
    check_program,
    check_programs,
    missing_folder,
)
from launchkit.runtime.process_io import POLL_INTERVAL, ProcessIO
from launchkit.runtime.process_report import ProcessReport
from launchkit.runtime.signals import (
    Interrupted,
    SignalPipe,
    exit_status,
    first_signal_message,
)
from launchkit.runtime.timers import TimerQueue

if TYPE_CHECKING:
    from launchkit.description.launch_context import DelayedActions, LaunchContext, Snapshot
    from launchkit.description.launch_description import LaunchDescription
    from launchkit.runtime.network import NodeNetwork


class Supervisor:
    """Runs a launch description and supervises what it starts (the :class:`Runner`), and
    the processes its processes ask for (the ``ChildHost`` of the child-request socket)."""

    def __init__(
        self,
        output: Output,
        *,
        network: NodeNetwork | None = None,
        clock: Callable[[], float] = time.monotonic,
        hooks: SupervisorHooks | None = None,
        process_factory: ProcessFactory | None = None,
        remote_factory: ProcessFactory | None = None,
    ) -> None:
        self.output = output
        self.hooks = self._relay = EventRelay(hooks or SupervisorHooks())
        self.network = network
        self.clock = clock
        self.processes: list[SupervisedProcess] = []
        self.exit_code = 0
        self.shutting_down = False
        self._context: LaunchContext | None = None
        self._pending: list[ProcessSpec] | None = None
        self._timers = TimerQueue()
        self._announcements = Announcements(output)
        self._interrupts = 0
        self._cleanup = LaunchCleanup()
        self._selector = selectors.DefaultSelector()
        self._signals = SignalPipe()
        self._io = ProcessIO(self._selector, output, self.hooks, self._on_exit)
        self._report = ProcessReport(output, self.hooks)
        self._requests: ChildRequests | None = None
        local = process_factory or (
            lambda spec, label, index: ManagedProcess(spec, label, index, self._cleanup.watch)
        )
        # processes for another host (spec.machine) are run by its agent (launchkit.remote)
        self._new_process = by_machine(local, remote_factory)

    # -- the Runner protocol (what actions call) ----------------------------------------------

    def start_process(self, spec: ProcessSpec) -> None:
        """Start ``spec`` now, or after the first pass when the launch is starting up."""
        if self._pending is not None:
            self._pending.append(spec)
        elif self.shutting_down:
            self.log("WARNING", "launch", f"not starting '{spec.name}': shutting down")
        else:
            with self._signals.deferred():
                self._start_new(spec)

    def schedule_timer(self, period: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Fire ``timer`` ``period`` seconds after the evaluation setting it (see timers.py)."""
        self._timers.add(period, timer, snapshot)

    def request_shutdown(self, reason: str) -> None:
        """``<shutdown>``: stop everything."""
        with self._signals.deferred():
            self.begin_shutdown(f"shutdown requested: {reason}", cause=reason)

    def log(self, level: str, logger: str, message: str) -> None:
        """A launch line."""
        self.output.launch_line(level, logger, message)

    def announce(self, logger: str, text: str) -> None:
        """A line for the user (``{"op": "announce"}``), held until the console settles."""
        self._announcements.hold(logger, text, self.clock())

    def stop_processes(self, matcher: Callable[[object], bool], signum: int | None) -> None:
        """ShutdownProcess (``signum`` None) / SignalProcess for the matching processes."""
        for process in [p for p in self.processes if p.alive and matcher(p.spec.origin)]:
            if signum is None:
                self.stop_child(process)
            else:
                self._send(process, SendSignal(signal.Signals(signum)))

    # -- running -----------------------------------------------------------------------------

    def run(self, description: LaunchDescription, context: LaunchContext) -> int:
        """Execute ``description`` and supervise until everything has stopped; the exit status.

        Errors in the first pass (before anything started) propagate as exceptions.
        """
        self._context = self._relay.attach(context, self._selector)
        self._signals.install()
        self._selector.register(self._signals.fd, selectors.EVENT_READ, self._read_signals)
        try:
            context.scratch_root = self._folder
            context.child_groups = self._cleanup
            context.uninterrupted = self._signals.deferred
            self._first_pass(description, context)
            self._timers.arm(self.clock())  # the timers it set count from now
            self.hooks.launch_ready()
            self._relay.drain(self.fail)
            while True:
                while not self._done():
                    self.step(self._timeout())
                if not self._went_idle():
                    break
        finally:
            self.close()
        return self.exit_code

    def _folder(self) -> Path:
        """The launch's private run folder, with the child-request socket in it: made when the
        first process starts or the first generated file is written (a launch that starts
        nothing spawns no orphan guard and opens no socket)."""
        folder = self._cleanup.folder
        if folder is None:
            folder = self._cleanup.open_folder()
            self._open_requests(folder)
        return Path(folder)

    def _open_requests(self, folder: str) -> None:
        try:
            self._requests = ChildRequests(self, self._selector, folder)
        except OSError as error:
            self.log(
                "WARNING",
                "launch",
                f"no child-request socket ({error}): processes that ask "
                "the launcher to start processes will run them themselves",
            )

    def _first_pass(self, description: LaunchDescription, context: LaunchContext) -> None:
        self._pending = []
        if description.deprecated is not None:
            self.log(
                "WARNING",
                "launch",
                f"launch file {description.path} is deprecated: {description.deprecated}",
            )
        try:
            with self._signals.interrupting(), context.in_file(description.path):
                for action in description.actions:
                    action.visit(context)
        except Interrupted:
            pass  # its signal is in the pipe: read below, like any other
        pending, self._pending = self._pending, None
        self._read_signals()
        if self.shutting_down:
            return
        check_programs([s for s in pending if not s.machine])  # another host's: its agent's
        for spec in pending:
            if self.shutting_down:
                break
            self._start_new(spec)

    def step(self, timeout: float | None) -> None:
        """One turn of the loop: wait up to ``timeout`` for output, exits, signals and
        requests, handle them, then whatever is due (timers, escalations, respawns)."""
        for key, _ in self._selector.select(timeout):
            # An earlier event of this batch may have unregistered this fd (a process
            # exited and its streams were closed; the number may even be reused already).
            if self._selector.get_map().get(key.fd) is not key:
                continue
            key.data()
        self._io.poll(self.processes)
        self._cleanup.sweep(self.clock())
        self._run_due()
        self._relay.drain(self.fail)  # the handlers of what happened; an error shuts down
        self._timers.arm(self.clock())

    def _done(self) -> bool:
        if any(p.alive for p in self.processes):
            return False
        if any(p.state is State.BACKOFF for p in self.processes) and not self.shutting_down:
            return False
        return not self._timers

    def _went_idle(self) -> bool:
        """Nothing runs or waits any more and nothing asked to shut down: as ROS, the launch
        shuts down with ``Shutdown(reason='idle')``, whose OnShutdown handlers run now (what
        they start keeps the loop going); False once it has."""
        if self.shutting_down:
            return False
        self.shutting_down = True
        self._timers.cancel_on_shutdown()
        if (error := self._relay.shutting_down("idle", False)) is not None:
            self.fail(error)
        self._timers.arm(self.clock())
        return True

    def _timeout(self) -> float | None:
        lifecycles = (p.lifecycle.deadline for p in self.processes)
        candidates = [self._timers.next_due(), self._announcements.deadline(), *lifecycles]
        deadlines = [d for d in candidates if d is not None]
        timeout = max(0.0, min(deadlines) - self.clock()) if deadlines else None
        if self._io.needs_polling:
            timeout = POLL_INTERVAL if timeout is None else min(timeout, POLL_INTERVAL)
        if self._cleanup.sweeping:
            timeout = SWEEP_PERIOD if timeout is None else min(timeout, SWEEP_PERIOD)
        return timeout

    def _run_due(self) -> None:
        now = self.clock()
        while (due := self._timers.pop_due(now)) is not None:
            self._fire(*due)
        for process in list(self.processes):
            effect = process.lifecycle.due(now)
            if isinstance(effect, Respawn):
                self._spawn(process)
            elif effect is not None:
                self._send(process, effect)
        self._announcements.print_due(now, self.shutting_down)

    def _fire(self, timer: DelayedActions, snapshot: Snapshot) -> None:
        context = self._context
        assert context is not None
        try:
            with self._signals.interrupting(), context.restored(snapshot):
                for action in timer.actions:
                    action.visit(context)
            context.emit(ExecutionComplete(action=timer))
        except LaunchkitError as error:
            self.fail(error)
        except Interrupted:
            pass  # its signal is in the pipe: the loop reads it next

    def fail(self, error: LaunchkitError) -> None:
        """An error while running: report it where it happened and shut down, exit 1."""
        self.output.launch_error(error.format())
        self.hooks.launch_error(error.format())
        self.exit_code = self.exit_code or 1
        self.begin_shutdown("an error occurred", level="ERROR")

    # -- processes ---------------------------------------------------------------------------

    def _start_new(self, spec: ProcessSpec) -> None:
        try:  # which rclpy it gets (launchkit's face first on PYTHONPATH?), where the router is
            spec.env.update(child_environment(spec.cmd, spec.env))
            if spec.is_node and self.network is not None:
                spec.env.update(self.network.ensure(self))
            elif self.network is not None:
                spec.env.update(self.network.known())
        except LaunchkitError as error:
            self.fail(error)
            return
        process = self._managed(spec)
        self.processes.append(process)
        self._spawn(process)

    def _managed(self, spec: ProcessSpec) -> SupervisedProcess:
        folder = self._folder()
        if self._requests is not None:
            spec.env.update(self._requests.environment())
        spec.env[RUN_TMPDIR] = str(folder)
        index = len(self.processes) + 1
        return self._new_process(spec, f"{spec.name}-{index}", index)

    def _spawn(self, process: SupervisedProcess) -> None:
        self._cleanup.before_respawn(process)  # an earlier incarnation's leftovers go first
        try:
            process.spawn()
        except OSError as error:
            process.lifecycle.failed()
            self._report.could_not_start(process, error)
            if not missing_folder(process.spec):  # which fails only its process, as in ROS
                self.exit_code = self.exit_code or 1
                self.begin_shutdown("a process could not be started", level="ERROR")
            return
        process.lifecycle.started(self.clock())
        self._watch(process)

    def _watch(self, process: SupervisedProcess) -> None:
        self._report.started(process)
        self._io.watch(process)

    def _on_exit(self, process: SupervisedProcess) -> None:
        code = process.poll()
        if code is None:
            return
        self._io.exited(process)  # what it wrote is printed before saying it exited
        required = process.spec.on_exit_shutdown
        outcome = process.lifecycle.exited(
            code, self.clock(), respawn_allowed=not (self.shutting_down or required)
        )
        self._report.exited(process, code, outcome)
        self._cleanup.exited(process, shutting_down=self.shutting_down)
        if self.shutting_down:
            return
        if required:
            if code != 0 and not outcome.expected:  # not when the launch stopped it itself
                self.exit_code = self.exit_code or (code if code > 0 else 128 - code)
            self.begin_shutdown(
                f"process[{process.label}] was required: shutting down launched system"
            )
        else:
            self._report.respawn(process, outcome)

    # -- processes started at a process's request (the child-request socket's ChildHost) -----

    def owner_of(self, pid: int) -> SupervisedProcess | None:
        """The running process of the launch whose pid (and so session) is ``pid``."""
        return next((p for p in self.processes if p.alive and p.pid == pid), None)

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
            if missing_folder(spec):
                raise RequestError(f"its working folder '{spec.cwd}' does not exist") from None
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

    # -- shutdown ----------------------------------------------------------------------------

    def begin_shutdown(self, reason: str, level: str = "INFO", cause: str | None = None) -> None:
        """Cancel timers and respawns, run OnShutdown handlers, SIGINT every process group."""
        if self.shutting_down:
            return
        self.shutting_down = True
        self.log(level, "launch", reason)
        self.hooks.shutdown(reason)
        self._timers.cancel_on_shutdown()
        if (error := self._relay.shutting_down(cause or reason, self._interrupts > 0)) is not None:
            self.fail(error)  # reported; the shutdown goes on
        now = self.clock()
        for process in self.processes:
            effect = process.lifecycle.stop(now)
            if effect is not None:
                self._send(process, effect)

    def _send(self, process: SupervisedProcess, effect: SendSignal) -> None:
        """Carry out a signal the lifecycle decided on, saying so as ROS does."""
        self._report.signal(process, effect)
        process.signal_group(effect.signum)

    def _read_signals(self) -> None:
        for signum in self._signals.pending():
            self.handle_signal(signum)

    def handle_signal(self, signum: int) -> None:
        """A signal to the launcher: the first shuts down, the next ones escalate at once."""
        self._interrupts += 1
        name = signal.Signals(signum).name
        if self._interrupts == 1:
            self.log("WARNING", "launch", first_signal_message(signum))
            self.exit_code = self.exit_code or exit_status(signum)
            cause = "ctrl-c (SIGINT)" if signum == signal.SIGINT else name  # ROS's reasons
            self.begin_shutdown("shutting down", cause=cause)
            return
        stopping = [p for p in self.processes if p.alive]
        waiting = ", ".join(f"{p.label} [pid {p.pid}]" for p in stopping) or "nothing"
        self.log("WARNING", "launch", f"{name} again: escalating now; still waiting for {waiting}")
        now = self.clock()
        for process in stopping:
            effect = process.lifecycle.escalate(now)
            if effect is not None:
                self._send(process, effect)

    def close(self) -> None:
        """Last resort: SIGKILL every group still around, reap, release everything (the signal
        handlers last, so a signal during the cleanup cannot interrupt it)."""
        for process in self.processes:
            if process.alive:
                process.kill_leftovers()
                process.reap()
            for fd in list(process.streams):
                process.close_stream(fd)
            process.close_pidfd()
        if self._requests is not None:
            self._requests.close()
            self._requests = None
        if self.network is not None:
            self.network.close()
        if self._context is not None:
            self._context.cleanup()
        self._relay.close()
        self._cleanup.close()
        self._selector.close()
        self._signals.close()
