"""The supervisor: one loop that starts processes, reads their output, fires timers, handles
signals and shuts everything down, in order.

Everything happens on the main thread in :meth:`Supervisor.run`. Child exits are seen through
pidfds, output through non-blocking pipes, signals through a wakeup fd, all in one selector, so
a lifecycle line is printed only after the child's remaining output: lines stay chronological.

Processes of the launch may also ask the supervisor, over the child-request socket it serves on
the same loop (:mod:`launchkit.runtime.child_requests`), to start processes for them; those are
supervised exactly like declared ones and stopped when their owner's connection closes.
"""

from __future__ import annotations

import heapq
import os
import selectors
import shutil
import signal
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.runtime.child_requests import ChildRequests, RequestError
from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.orphan_guard import OrphanGuard
from launchkit.runtime.output import Output
from launchkit.runtime.process import ManagedProcess, State, describe_exit

if TYPE_CHECKING:
    from launchkit.description.launch_context import DelayedActions, LaunchContext, Snapshot
    from launchkit.description.launch_description import LaunchDescription
    from launchkit.runtime.network import NodeNetwork

HANDLED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)
_ESCALATION = {signal.SIGINT: signal.SIGTERM, signal.SIGTERM: signal.SIGKILL}
_POLL_INTERVAL = 0.05  # only when the kernel has no pidfd_open


class Supervisor:
    """Runs a launch description and supervises what it starts (the :class:`Runner`)."""

    def __init__(
        self,
        output: Output,
        *,
        network: NodeNetwork | None = None,
        clock: Callable[[], float] = time.monotonic,
        hooks: SupervisorHooks | None = None,
    ) -> None:
        self.output = output
        self.hooks = hooks or SupervisorHooks()
        self.network = network
        self.clock = clock
        self.processes: list[ManagedProcess] = []
        self.exit_code = 0
        self.shutting_down = False
        self._context: LaunchContext | None = None
        self._pending: list[ProcessSpec] | None = None
        self._timers: list[tuple[float, int, DelayedActions, Snapshot]] = []
        self._timer_seq = 0
        self._interrupts = 0
        self._lingering: set[int] = set()
        self._guard = OrphanGuard()
        self._selector = selectors.DefaultSelector()
        self._signal_r, self._signal_w = os.pipe()
        self._needs_polling = False
        self._requests: ChildRequests | None = None
        self.on_started: Callable[[ManagedProcess], None] | None = None

    # -- the Runner protocol (what actions call) ----------------------------------------------

    def start_process(self, spec: ProcessSpec) -> None:
        """Start ``spec`` now, or after the first pass when the launch is starting up."""
        if self._pending is not None:
            self._pending.append(spec)
        elif self.shutting_down:
            self.log("WARNING", "launch", f"not starting '{spec.name}': shutting down")
        else:
            self._start_new(spec)

    def schedule_timer(self, period: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Fire ``timer`` after ``period`` seconds."""
        self._timer_seq += 1
        heapq.heappush(self._timers, (self.clock() + period, self._timer_seq, timer, snapshot))

    def request_shutdown(self, reason: str) -> None:
        """``<shutdown>``: stop everything."""
        self.begin_shutdown(f"shutdown requested: {reason}")

    def log(self, level: str, logger: str, message: str) -> None:
        """A launch line."""
        self.output.launch_line(level, logger, message)

    # -- running -----------------------------------------------------------------------------

    def run(self, description: LaunchDescription, context: LaunchContext) -> int:
        """Execute ``description`` and supervise until everything has stopped; the exit status.

        Errors in the first pass (before anything started) propagate as exceptions.
        """
        self._context = context
        previous = self._install_signals()
        try:
            self._open_requests()
            self._first_pass(description, context)
            self.hooks.launch_ready()
            self._loop()
        finally:
            self._finish()
            for signum, handler in previous.items():
                signal.signal(signum, handler)
            signal.set_wakeup_fd(-1)
        return self.exit_code

    def _open_requests(self) -> None:
        try:
            self._requests = ChildRequests(self, self._selector)
        except OSError as error:
            self.log(
                "WARNING",
                "launch",
                f"no child-request socket ({error}): processes that ask "
                "the launcher to start processes will run them themselves",
            )
            return
        self._guard.remove_on_death(self._requests.folder)

    def _first_pass(self, description: LaunchDescription, context: LaunchContext) -> None:
        self._pending = []
        if description.deprecated is not None:
            self.log(
                "WARNING",
                "launch",
                f"launch file {description.path} is deprecated: {description.deprecated}",
            )
        with context.in_file(description.path):
            for action in description.actions:
                action.visit(context)
        pending, self._pending = self._pending, None
        for spec in pending:
            check_program(spec)
        self._read_signals()
        for spec in pending:
            if self.shutting_down:
                break
            self._start_new(spec)

    def _loop(self) -> None:
        while not self._done():
            timeout = self._timeout()
            for key, _ in self._selector.select(timeout):
                # An earlier event of this batch may have unregistered this fd (a process
                # exited and its streams were closed; the number may even be reused already).
                if self._selector.get_map().get(key.fd) is not key:
                    continue
                key.data()
            if self._needs_polling:
                for process in list(self.processes):
                    if process.alive and process.pidfd is None and process.poll() is not None:
                        self._on_exit(process)
            self._run_due()

    def _done(self) -> bool:
        if any(p.alive for p in self.processes):
            return False
        if any(p.state is State.BACKOFF for p in self.processes) and not self.shutting_down:
            return False
        return not self._timers

    def _timeout(self) -> float | None:
        deadlines = [t[0] for t in self._timers[:1]]
        deadlines += [p.escalation_at for p in self.processes if p.escalation_at is not None]
        deadlines += [p.respawn_at for p in self.processes if p.respawn_at is not None]
        timeout = max(0.0, min(deadlines) - self.clock()) if deadlines else None
        if self._needs_polling:
            timeout = _POLL_INTERVAL if timeout is None else min(timeout, _POLL_INTERVAL)
        return timeout

    def _run_due(self) -> None:
        now = self.clock()
        while self._timers and self._timers[0][0] <= now:
            _, _, timer, snapshot = heapq.heappop(self._timers)
            self._fire(timer, snapshot)
        for process in list(self.processes):
            if process.escalation_at is not None and process.escalation_at <= now:
                self._escalate(process)
            if process.respawn_at is not None and process.respawn_at <= now:
                process.respawn_at = None
                self._spawn(process)

    def _fire(self, timer: DelayedActions, snapshot: Snapshot) -> None:
        context = self._context
        assert context is not None
        try:
            with context.restored(snapshot):
                for action in timer.actions:
                    action.visit(context)
        except LaunchkitError as error:
            self.fail(error)

    def fail(self, error: LaunchkitError) -> None:
        """An error while running: report it where it happened and shut down, exit 1."""
        self.output.launch_line("ERROR", "launch", error.format())
        self.hooks.launch_error(error.format())
        self.exit_code = self.exit_code or 1
        self.begin_shutdown("an error occurred", level="ERROR")

    # -- processes ---------------------------------------------------------------------------

    def _start_new(self, spec: ProcessSpec) -> None:
        if spec.is_node and self.network is not None:
            try:
                spec.env.update(self.network.ensure(self))
            except LaunchkitError as error:
                self.fail(error)
                return
        elif self.network is not None:
            spec.env.update(self.network.known())
        process = self._managed(spec)
        self.processes.append(process)
        self._spawn(process)

    def _managed(self, spec: ProcessSpec) -> ManagedProcess:
        if self._requests is not None:
            spec.env.update(self._requests.environment())
        index = len(self.processes) + 1
        return ManagedProcess(spec, f"{spec.name}-{index}", index)

    def _spawn(self, process: ManagedProcess) -> None:
        try:
            process.spawn()
        except OSError as error:
            process.state = State.FAILED
            where = f" ({process.spec.location})" if process.spec.location else ""
            message = f"could not start process: {error.strerror}: '{process.spec.cmd[0]}'{where}"
            self.log("ERROR", process.label, message)
            self.hooks.launch_error(f"{process.label}: {message}")
            self.exit_code = self.exit_code or 1
            self.begin_shutdown("a process could not be started", level="ERROR")
            return
        self._watch(process)

    def _watch(self, process: ManagedProcess) -> None:
        assert process.popen is not None
        self._guard.watch(process.popen.pid)
        self.log("INFO", process.label, f"process started with pid [{process.pid}]")
        for fd in process.streams:
            self._selector.register(fd, selectors.EVENT_READ, _bind(self._on_output, process, fd))
        if process.pidfd is not None:
            self._selector.register(
                process.pidfd, selectors.EVENT_READ, _bind(self._on_exit, process)
            )
        else:
            self._needs_polling = True
        self.hooks.process_started(process)
        if self.on_started is not None:
            self.on_started(process)

    def _on_output(self, process: ManagedProcess, fd: int) -> None:
        lines, eof = process.read(fd)
        kind = process.streams[fd].kind
        for line in lines:
            self.output.child_line(process.label, process.index, line, process.spec.output, kind)
            self.hooks.process_output(process, kind, line)
        if eof:
            self._selector.unregister(fd)
            process.close_stream(fd)

    def _on_exit(self, process: ManagedProcess) -> None:
        code = process.poll()
        if code is None:
            return
        if process.pidfd is not None:
            self._selector.unregister(process.pidfd)
            os.close(process.pidfd)
            process.pidfd = None
        for fd in list(process.streams):
            self._on_output(process, fd)  # print what it wrote before saying it exited
        process.returncode = code
        stopping = process.state is State.STOPPING
        process.state = State.EXITED
        process.escalation_at = None
        self._report_exit(process, code, stopping)
        self.hooks.process_exited(process, code)
        if _group_exists(process.pid):
            if self.shutting_down:
                process.kill_leftovers()
            else:
                self._lingering.add(process.pid or 0)
        if self.shutting_down:
            return
        if process.spec.on_exit_shutdown:
            if code != 0:
                self.exit_code = self.exit_code or (code if code > 0 else 128 - code)
            self.begin_shutdown(
                f"process[{process.label}] was required: shutting down launched system"
            )
        elif process.spec.respawn and not process.retired:
            self._maybe_respawn(process)

    def _report_exit(self, process: ManagedProcess, code: int, stopping: bool) -> None:
        pid = process.pid
        if code == 0:
            self.log("INFO", process.label, f"process has finished cleanly [pid {pid}]")
        elif stopping and code < 0 and -code in process.signals_sent:
            self.log(
                "INFO", process.label, f"process has finished [pid {pid}, {describe_exit(code)}]"
            )
        else:
            cmd = process.spec.command_line()
            self.log(
                "ERROR",
                process.label,
                f"process has died [pid {pid}, {describe_exit(code)}, cmd '{cmd}'].",
            )

    def _maybe_respawn(self, process: ManagedProcess) -> None:
        limit = process.spec.respawn_max_retries
        if 0 <= limit <= process.retries:
            self.log("WARNING", process.label, f"not respawning: {limit} retries used")
            return
        process.retries += 1
        process.state = State.BACKOFF
        process.respawn_at = self.clock() + process.spec.respawn_delay
        self.log("INFO", process.label, f"respawning in {process.spec.respawn_delay:g} s")

    # -- processes started on request (the ChildHost protocol of child_requests) -------------

    def owner_of(self, pid: int) -> ManagedProcess | None:
        """The running process of the launch whose pid (and so session) is ``pid``."""
        return next((p for p in self.processes if p.alive and p.pid == pid), None)

    def start_child(self, spec: ProcessSpec, owner: ManagedProcess) -> ManagedProcess:
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
        self.processes.append(process)
        self.log("INFO", process.label, f"started at the request of {owner.label}")
        self._watch(process)
        return process

    def stop_child(self, process: ManagedProcess) -> None:
        """Stop a process started on request, as a shutdown would, and never respawn it."""
        process.retired = True
        if process.state is State.BACKOFF:
            process.state = State.EXITED
            process.respawn_at = None
        elif process.state is State.RUNNING:
            self.hooks.process_stopping(process)
            self._send(process, signal.SIGINT)

    # -- shutdown ----------------------------------------------------------------------------

    def begin_shutdown(self, reason: str, level: str = "INFO") -> None:
        """Cancel timers and respawns and send SIGINT to every running process group."""
        if self.shutting_down:
            return
        self.shutting_down = True
        self.log(level, "launch", reason)
        self.hooks.shutdown(reason)
        self._timers = [t for t in self._timers if not t[2].cancel_on_shutdown]
        heapq.heapify(self._timers)
        for process in self.processes:
            if process.state is State.BACKOFF:
                process.state = State.EXITED
                process.respawn_at = None
            if process.state is State.RUNNING:
                self._send(process, signal.SIGINT)

    def _send(self, process: ManagedProcess, signum: int) -> None:
        name = signal.Signals(signum).name
        self.log("INFO", process.label, f"sending signal '{name}' to process[{process.label}]")
        process.signal_group(signum)
        process.state = State.STOPPING
        timeout = {
            signal.SIGINT: process.spec.sigterm_timeout,
            signal.SIGTERM: process.spec.sigkill_timeout,
        }.get(signal.Signals(signum))
        process.escalation_at = None if timeout is None else self.clock() + timeout

    def _escalate(self, process: ManagedProcess, announce: bool = True) -> None:
        last = signal.Signals(process.signals_sent[-1]) if process.signals_sent else signal.SIGINT
        following = _ESCALATION.get(last)
        if following is None:
            process.escalation_at = None
            return
        if announce:
            waited = (
                process.spec.sigterm_timeout
                if last is signal.SIGINT
                else process.spec.sigkill_timeout
            )
            self.log(
                "ERROR",
                process.label,
                f"process[{process.label}] failed to terminate '{waited:g}' seconds after "
                f"receiving '{last.name}', escalating to '{following.name}'",
            )
        self._send(process, following)

    def _read_signals(self) -> None:
        try:
            data = os.read(self._signal_r, 512)
        except BlockingIOError:
            return
        for signum in data:
            self._on_signal(signum)

    def _on_signal(self, signum: int) -> None:
        self._interrupts += 1
        name = signal.Signals(signum).name
        if self._interrupts == 1:
            what = (
                "user interrupted with ctrl-c (SIGINT)"
                if signum == signal.SIGINT
                else f"received {name}"
            )
            self.log("WARNING", "launch", what)
            self.begin_shutdown("shutting down")
            return
        stopping = [p for p in self.processes if p.alive]
        waiting = ", ".join(f"{p.label} [pid {p.pid}]" for p in stopping) or "nothing"
        self.log("WARNING", "launch", f"{name} again: escalating now; still waiting for {waiting}")
        for process in stopping:
            self._escalate(process, announce=False)

    def _install_signals(self) -> dict[int, signal._HANDLER]:
        os.set_blocking(self._signal_r, False)
        os.set_blocking(self._signal_w, False)
        signal.set_wakeup_fd(self._signal_w, warn_on_full_buffer=False)
        self._selector.register(self._signal_r, selectors.EVENT_READ, self._read_signals)
        previous: dict[int, signal._HANDLER] = {}
        for signum in HANDLED_SIGNALS:
            previous[signum] = signal.signal(signum, _ignore)
        return previous

    def _finish(self) -> None:
        """Last resort: SIGKILL every group still around, reap, release everything."""
        for process in self.processes:
            if process.alive:
                process.kill_leftovers()
                if process.popen is not None:
                    process.popen.wait()
            for fd in list(process.streams):
                process.close_stream(fd)
            if process.pidfd is not None:
                os.close(process.pidfd)
                process.pidfd = None
        for pgid in self._lingering:
            try:
                os.killpg(pgid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        self._guard.dismiss()
        if self._requests is not None:
            self._requests.close()
            self._requests = None
        if self.network is not None:
            self.network.close()
        if self._context is not None:
            self._context.cleanup()
        self._selector.close()
        os.close(self._signal_r)
        os.close(self._signal_w)


def _bind(function: Callable[..., None], *args: object) -> Callable[[], None]:
    return lambda: function(*args)


def _ignore(signum: int, frame: object) -> None:
    """Python-level handler: the wakeup fd carries the signal to the loop."""


def _group_exists(pgid: int | None) -> bool:
    if not pgid:
        return False
    try:
        os.killpg(pgid, 0)
    except (ProcessLookupError, PermissionError):
        return False
    return True


def check_program(spec: ProcessSpec) -> None:
    """Fail before anything starts when a process's program does not exist."""
    program = spec.cmd[0]
    if "/" in program:
        path = program if os.path.isabs(program) else os.path.join(spec.cwd or os.getcwd(), program)
        if os.access(path, os.X_OK) and os.path.isfile(path):
            return
    elif shutil.which(program, path=spec.env.get("PATH", os.defpath)):
        return
    raise LaunchFileError(
        f"program '{program}' of process '{spec.name}' not found",
        spec.location,
        expected="an executable file, or a program on the PATH",
    )
