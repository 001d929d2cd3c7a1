"""A launch running in the background for a test: starting it, waiting on it, stopping it."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import threading
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from launchkit.envvars import ROUTER as ROUTER_ENV
from launchkit.envvars import VIEWER_PORT as VIEWER_PORT_ENV
from launchkit.runtime.lifecycle import Escalation, escalate_until_exited
from launchkit.runtime.process import describe_exit
from launchkit.testing import _procscan
from launchkit.testing._deadline import Deadline
from launchkit.testing._errors import (
    LaunchFailed,
    LaunchTestError,
    ProcessDied,
    ProcessLeftBehind,
    UnexpectedExit,
    WaitTimeout,
)
from launchkit.testing._evidence import (
    describe_launch,
    launcher_lines,
    process_title,
    report_sections,
    tail,
)
from launchkit.testing._isolation import (
    ROS_DOMAIN_ENV,
    domain_id,
    free_loopback_port,
    router_endpoint,
    without_shell_settings,
)
from launchkit.testing._process import ProcessHandle
from launchkit.testing._result import LaunchResult
from launchkit.testing._state import LaunchState
from launchkit.testing._waits import AllowedExits, AllowExit, Waits

if TYPE_CHECKING:
    from launchkit.testing._sim_clock import SimClock
    from launchkit.testing._topics import TopicProbe

DEFAULT_READY_TIMEOUT = 30.0
_STOP_MARGIN = 5.0  # beyond the launcher's own SIGINT -> SIGTERM -> SIGKILL escalation
_AFTER_SIGTERM = 2.0
_VANISH = 1.0  # for processes already killed to disappear from /proc
_REPORT_LINES = 500

# launches not yet stopped, for the plugin's backstops (session end, interrupt, exit)
LIVE: set[LaunchHandle] = set()


class LaunchHandle:
    """A launch started with ``launchkit run`` in its own session, observed through its event
    channel. Get one from the ``launch`` fixture; stop it with :meth:`stop` (the fixture stops
    it at the end of the test otherwise)."""

    def __init__(
        self,
        items: list[str],
        *,
        log_dir: Path,
        title: str,
        env: Mapping[str, str] | None = None,
        cwd: str | os.PathLike[str] | None = None,
        allow_exit: AllowExit | None = None,
        lockstep: bool = False,
    ) -> None:
        self.title = title
        self.log_dir = log_dir
        self.launcher_log = log_dir / "launcher.log"
        self.router = router_endpoint(free_loopback_port())
        self.domain_id = domain_id()
        self.state = LaunchState()
        self.waits = Waits(self.state, title, self.launcher_log, AllowedExits(allow_exit))
        self._probe: TopicProbe | None = None
        self.lockstep = lockstep
        self._sim_clock: SimClock | None = None
        self.stop_notes: list[str] = []
        self._stop_waits: list[float] = []  # scaled seconds each stop signal was given
        self._result: LaunchResult | None = None
        environment = {
            **without_shell_settings(os.environ),
            "ROS_LOG_DIR": str(log_dir / "ros"),
            "PYTHONUNBUFFERED": "1",
            VIEWER_PORT_ENV: str(free_loopback_port()),
            **(env or {}),
            **self.ros_env,
        }
        # the rviz2 stand-in's port, unless the launch file gives it one (viewer_port:=...)
        self.viewer_port = int(environment[VIEWER_PORT_ENV])
        ours, theirs = socket.socketpair()
        fd = theirs.fileno()
        command = [sys.executable, "-m", "launchkit", "run", "--router", self.router]
        command += ["--events-fd", str(fd), *(["--lockstep-paused"] if lockstep else []), *items]
        try:
            with open(self.launcher_log, "wb") as log:
                self._popen = subprocess.Popen(
                    command,
                    stdin=subprocess.DEVNULL,
                    stdout=log,
                    stderr=subprocess.STDOUT,
                    env=environment,
                    cwd=cwd,
                    start_new_session=True,
                    pass_fds=[fd],
                )
        except BaseException:
            ours.close()
            raise
        finally:
            theirs.close()
        self._channel = ours
        self.pid = self._popen.pid
        LIVE.add(self)
        self._reader = threading.Thread(
            target=self._read_events, name=f"launchkit-events-{self.pid}", daemon=True
        )
        self._reader.start()

    def __repr__(self) -> str:
        return f"<LaunchHandle {self.title} pid {self.pid}>"

    @property
    def ros_env(self) -> dict[str, str]:
        """What a process needs in its environment to join this launch's ROS network (for
        example ``launchkit topic echo`` run by the test with ``env={**os.environ, **ros_env}``)."""
        return {ROUTER_ENV: self.router, ROS_DOMAIN_ENV: str(self.domain_id)}

    # -- the event channel ---------------------------------------------------------------------

    def _read_events(self) -> None:
        try:
            with self._channel.makefile("rb") as stream:
                for line in stream:
                    try:
                        event = json.loads(line)
                    except ValueError:
                        continue  # not ours; the launcher's output goes to its log file
                    if isinstance(event, dict):
                        self.state.apply(event)
        except OSError:
            pass
        finally:
            # whatever happened, waits must learn that nothing more will come
            self.state.close_channel()
            self.state.launcher_exited(self._popen.wait())

    # -- readiness -----------------------------------------------------------------------------

    def wait_ready(self, timeout: float = DEFAULT_READY_TIMEOUT) -> None:
        """Wait until the launcher has started what the file starts at once. If the launch
        fails first, stop it and raise :class:`LaunchFailed` with launchkit's own message."""
        __tracebackhide__ = True
        deadline = Deadline(timeout)
        state = self.state
        with state.condition:
            while not (state.ready or state.failure or state.channel_closed):
                if deadline.expired():
                    break
                state.condition.wait(deadline.remaining())
            if state.ready and not state.errors:
                return
            ended = state.channel_closed
            # an error in the first pass (a process that could not be spawned) fails it too
            failure = state.failure or (state.errors[0] if state.errors else None)
            evidence = describe_launch(state, self.launcher_log)
        _, leftovers = self._shutdown(None)
        if leftovers:
            found = ", ".join(str(process) for process in leftovers)
            failure = (failure or "") + f"\n(and these survived its teardown: {found})"
        if failure is not None:
            raise LaunchFailed(f"{self.title} failed before it was ready:\n{failure}")
        if ended:
            code = self._popen.returncode
            status = "" if code is None else f" (launcher {describe_exit(code)})"
            printed = "\n".join(tail(launcher_lines(self.launcher_log)))
            raise LaunchFailed(f"{self.title} ended before it was ready{status}:\n{printed}")
        raise LaunchFailed(
            f"{self.title} was not ready after {deadline.seconds:g} s "
            f"(the launcher had not finished starting its processes)\n{evidence}"
        )

    # -- processes and waits -------------------------------------------------------------------

    def process(self, name: str) -> ProcessHandle:
        """The process ``name`` names: its ``name`` attribute, executable or ROS node name (no
        ``-N`` suffix), or its ``name-N`` label. It may start later (see ``wait_running``)."""
        __tracebackhide__ = True
        handle = ProcessHandle(self, name)
        with self.state.condition:
            handle._find()  # an ambiguous name fails here, at once
        return handle

    def process_names(self) -> str:
        """``talker-1 (talker), ...``: the processes so far, for messages."""
        with self.state.condition:
            return ", ".join(process_title(r) for r in self.state.processes.values())

    @property
    def output(self) -> dict[str, list[str]]:
        """Every process's lines so far, by label."""
        with self.state.condition:
            return {
                label: [line.text for line in record.lines]
                for label, record in self.state.processes.items()
            }

    def check_exits_noted(self) -> None:
        """Raise :class:`UnexpectedExit` if a process died unexpectedly and the test never
        took note of it (the fixtures call this at teardown, after stopping the launch)."""
        __tracebackhide__ = True
        if self._result is not None and self._result.noted:
            return
        with self.state.condition:
            verdict = self.waits.teardown_verdict()
        if verdict is not None:
            raise UnexpectedExit(verdict)

    # -- topics --------------------------------------------------------------------------------

    def expect_topic(
        self,
        topic: str,
        min_messages: int = 1,
        within: float = 10.0,
        where: Callable[[Any], bool] | None = None,
    ) -> list[Any]:
        """Wait up to ``within`` seconds for ``min_messages`` messages on ``topic`` (those for
        which ``where(message)`` holds, when given) and return them.

        The test process joins the launch's own ROS network for this; the subscription takes the
        publisher's QoS, so a latched topic's last message counts. Raises :class:`WaitTimeout`
        saying what arrived, or :class:`ProcessDied` at once if the launch can no longer
        deliver (it failed or ended, or a required process died).
        """
        __tracebackhide__ = True
        from launchkit.testing._topics import TopicProbe, TopicTimeout

        what = f"{min_messages} message(s) on {topic}" + (
            " matching the condition" if where else ""
        )
        if self._probe is None:
            self._probe = TopicProbe(self.router, self.domain_id)

        def check() -> None:
            with self.state.condition:
                problem = self.waits.launch_over()
                if problem is not None:
                    raise ProcessDied(self.waits.failure(what, problem))

        try:
            return self._probe.expect(topic, min_messages, Deadline(within), where, check)
        except TopicTimeout as why:
            with self.state.condition:
                raise WaitTimeout(self.waits.failure(what, f"timed out: {why}")) from None

    # -- simulated time (lockstep=True) --------------------------------------------------------

    def _clock(self) -> SimClock:
        if not self.lockstep:
            raise LaunchTestError(
                f"{self.title} does not run in lockstep (launch(..., lockstep=True))"
            )
        if self._sim_clock is None:
            from launchkit.testing._sim_clock import SimClock

            self._sim_clock = SimClock(self.router, self.domain_id)
        return self._sim_clock

    @property
    def sim_time(self) -> float:
        """The launch's simulated time in seconds (``lockstep=True``)."""
        return self._clock().sim_time

    def advance(self, seconds: float, timeout: float = 60.0) -> float:
        """Run the simulated time ``seconds`` forward; returns, with the new time, once every
        node has handled everything due up to it (at most ``timeout`` wall seconds)."""
        __tracebackhide__ = True
        return self._sim_wait(lambda clock, deadline: clock.advance(seconds, deadline), timeout)

    def wait_until(
        self, condition: Callable[[], bool], within: float, step: float = 0.1, timeout: float = 60.0
    ) -> float:
        """Advance the simulated time by ``step`` until ``condition()`` holds, for at most
        ``within`` simulated seconds; the simulated time it held at."""
        __tracebackhide__ = True
        return self._sim_wait(
            lambda clock, deadline: clock.wait_until(condition, within, step, deadline), timeout
        )

    def publish(self, topic: str, message: Any) -> None:
        """Publish ``message`` on ``topic`` from the test's node: the launch's nodes handle it
        before the simulated time next moves."""
        self._clock().publish(topic, message)

    def subscribe(self, topic: str, msg_type: Any) -> None:
        """Keep the latest message on ``topic``, delivered before ``advance`` returns."""
        self._clock().subscribe(topic, msg_type)

    def latest(self, topic: str) -> Any:
        """The latest message kept on a topic :meth:`subscribe` named (None: none yet)."""
        return self._clock().latest(topic)

    def _sim_wait(self, wait: Callable[[SimClock, Deadline], float], timeout: float) -> float:
        __tracebackhide__ = True
        from launchkit.testing._sim_clock import SimClockTimeout

        clock = self._clock()
        with self.state.condition:
            problem = self.waits.launch_over()
            if problem is not None:
                raise ProcessDied(self.waits.failure("simulated time", problem))
        try:
            return wait(clock, Deadline(timeout))
        except SimClockTimeout as why:
            with self.state.condition:
                raise WaitTimeout(
                    self.waits.failure("simulated time", f"timed out: {why}")
                ) from None

    # -- stopping ------------------------------------------------------------------------------

    def _close_probe(self) -> None:
        if self._probe is not None:
            probe, self._probe = self._probe, None
            probe.close()
        if self._sim_clock is not None:
            sim_clock, self._sim_clock = self._sim_clock, None
            sim_clock.close()

    @property
    def stopped(self) -> bool:
        """Whether :meth:`stop` has run."""
        return self._result is not None

    def stop(self, timeout: float | None = None) -> LaunchResult:
        """Stop the launch as Ctrl-C would (SIGINT; the launcher escalates every process to
        SIGTERM, then SIGKILL), escalate further if the launcher itself hangs, then check that
        no process of the launch survived. The result holds exit codes and output.

        ``timeout`` bounds the launcher's own shutdown (default: the slowest process's
        escalation time plus a margin). Raises :class:`ProcessLeftBehind` if a process
        survived; it has been killed by then. Calling it again returns the same result.
        """
        __tracebackhide__ = True
        if self._result is not None:
            return self._result
        result, leftovers = self._shutdown(timeout)
        if leftovers:
            found = "\n  ".join(str(process) for process in leftovers)
            raise ProcessLeftBehind(
                f"{len(leftovers)} process(es) of {self.title} survived its teardown "
                f"(killed now):\n  {found}\n{result.evidence}"
            )
        return result

    def _shutdown(self, timeout: float | None) -> tuple[LaunchResult, list[_procscan.LiveProcess]]:
        self._close_probe()
        state = self.state
        with state.condition:
            state.stopping = True
            slowest = max((r.escalation for r in state.processes.values()), default=0.0)
        if self._popen.poll() is None:
            budget = slowest + _STOP_MARGIN if timeout is None else timeout
            ladder = ((signal.SIGINT, budget), (signal.SIGTERM, _AFTER_SIGTERM))
            escalate_until_exited(
                Escalation((*ladder, (signal.SIGKILL, None))), self._stop_signal, self._stop_wait
            )
        self._popen.wait()
        self._reader.join(Deadline(_VANISH).seconds)
        self._channel.close()
        LIVE.discard(self)
        leftovers = _procscan.sweep([self.pid, *state.all_pids()], Deadline(_VANISH))
        self._result = self._make_result()
        return self._result, leftovers

    def _stop_signal(self, signum: signal.Signals) -> None:
        """One step of the stop: SIGINT to the launcher (it stops every process itself); if it
        hangs, SIGTERM to it and to every process group of the launch; then SIGKILL to all."""
        if signum == signal.SIGINT:
            self._signal_launcher(signum)
            return
        pids = self.state.all_pids()
        if signum == signal.SIGTERM:
            self.stop_notes.append(
                f"the launcher was still running {self._stop_waits[-1]:g} s after SIGINT: "
                "sent SIGTERM to it and to every process group of the launch"
            )
            self._signal_launcher(signum)
        else:
            self.stop_notes.append("the launcher still ran after SIGTERM: SIGKILL")
            pids = [self.pid, *pids]
        _procscan.kill_groups(pids, signum)

    def _stop_wait(self, seconds: float | None) -> bool:
        """Whether the launcher exits within ``seconds`` (scaled); None: reaped afterwards."""
        if seconds is None:
            return True
        deadline = Deadline(seconds)
        self._stop_waits.append(deadline.seconds)
        return self._await_launcher(deadline)

    def _signal_launcher(self, signum: int) -> None:
        try:
            os.kill(self.pid, signum)
        except ProcessLookupError:
            pass

    def _await_launcher(self, deadline: Deadline) -> bool:
        state = self.state
        with state.condition:
            while state.launcher_returncode is None and not deadline.expired():
                state.condition.wait(deadline.remaining())
            return state.launcher_returncode is not None

    def _make_result(self) -> LaunchResult:
        with self.state.condition:
            evidence = describe_launch(self.state, self.launcher_log)
            return LaunchResult.of(self.state, self._popen.returncode, evidence)

    def kill(self) -> None:
        """SIGKILL the launch and everything it started at once (a backstop, not a stop)."""
        _procscan.kill_groups([self.pid, *self.state.all_pids()], signal.SIGKILL)

    # -- reporting -----------------------------------------------------------------------------

    def report_sections(self) -> list[tuple[str, str]]:
        """(title, text) per process and for the launcher, for a failing test's report."""
        with self.state.condition:
            return report_sections(
                self.title, self.state, self.launcher_log, self.stop_notes, _REPORT_LINES
            )


__all__ = ["LaunchHandle", "LaunchTestError"]
