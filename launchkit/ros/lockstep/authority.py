"""The time authority of a lockstep launch: publishes ``/clock``, advancing it only when the
launch is quiescent (:mod:`.quiescence`), to the next instant a participant has something due.

It runs in a thread of the launcher, which tells it the processes it starts and sees exit
(:meth:`TimeAuthority.expect`, :meth:`TimeAuthority.exited`): the time stands still until a new
process has joined (its first report), so what it does happens at the same simulated time in
every run. A process that has not joined after ``join_grace`` wall seconds (a shell script, a
program on the real rclpy) is named as outside the lockstep and no longer waited for.

Without ``rtf`` the time advances as fast as the slowest participant allows; with it, no faster
than ``rtf`` simulated seconds per wall second. ``until`` ends the launch (``on_until``) at that
simulated time. ``paused`` holds the time until a test asks for more (:data:`.report.CONTROL_KEY`:
``{"run_until_ns": N}``) and says where it is on :data:`.report.STATUS_KEY` (only then: the
test plugin is its one reader, and a status at every instant costs a put each).
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from launchkit.ros.lockstep.participant import Participant
from launchkit.ros.lockstep.quiescence import Quiescence
from launchkit.ros.lockstep.report import CONTROL_KEY, REPORTS, STATUS_KEY, WAKE_KEY, Report

_NS = 1_000_000_000
#: Wall seconds between two re-sends of ``/clock`` to a participant that has not reached it.
_RESEND = 0.2
#: Wall seconds the time may stand still before the authority says why (once per instant).
_STALL_NOTE = 10.0


@dataclass(frozen=True)
class ClockOptions:
    """How a lockstep launch runs its time (``launchkit run --lockstep`` options)."""

    rtf: float | None = None  # at most this many simulated seconds per wall second
    until: float | None = None  # end the launch at this simulated time (seconds)
    paused: bool = False  # advance only on request (the test plugin)
    max_step: float = 0.1  # the most the time moves in one step (seconds)
    clock_period: float = 0.1  # /clock at least this often in simulated seconds (10 Hz)
    join_grace: float = 10.0  # wall seconds a started process has to join


class TimeAuthority:
    """Owns the launch's simulated time (see the module's docstring)."""

    def __init__(
        self,
        router: str,
        options: ClockOptions,
        log: Callable[[str, str], None],
        on_until: Callable[[], None],
        domain_id: int | None = None,
    ) -> None:
        from launchkit.ros.context import Context

        self.options = options
        self._log = log
        self._on_until = on_until
        self._context = Context(router=router, start_router=False)
        self._context.init([], domain_id)
        # stamps /clock with the simulated time, as a participant's publishers are
        self._stamp = self._context.lockstep = Participant(self._context, "lockstep clock")
        self._state = Quiescence()
        self._expected: dict[int, tuple[str, float]] = {}  # pid -> (label, wall time started)
        self._changed = threading.Condition()
        self._news = False  # a report, a process or a request came since the loop last looked
        self._stopped = False
        self._started_all = False  # the launch has started what it starts at once
        self._time_ns = 0
        self._steps = 0  # instants the time has moved to
        self._target_ns: int | None = 0 if options.paused else None
        self._until_ns = None if options.until is None else round(options.until * _NS)
        self._pace_anchor: tuple[float, int] | None = None
        self._clock_published_ns = 0
        self._clock_pub: Any = None
        self._thread = threading.Thread(target=self._run, name="lockstep-clock", daemon=True)

    # what the launcher calls (its loop) ---------------------------------------------------
    def start(self) -> None:
        """Publish the time 0 and start deciding."""
        import launchkit.ros as ros
        from launchkit.ros.msgs import get_message

        node = ros.Node(
            "lockstep_clock",
            context=self._context,
            enable_rosout=False,
            start_parameter_services=False,
            parameter_overrides=[ros.Parameter("use_sim_time", value=False)],
        )
        qos = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
        self._clock_type = get_message("rosgraph_msgs/msg/Clock")
        self._clock_pub = node.create_publisher(self._clock_type, "/clock", qos)
        session = self._context.session
        domain = self._context.domain_id
        self._subs = [
            session.declare_subscriber(REPORTS.format(domain=domain), self._on_report),
            session.declare_subscriber(CONTROL_KEY.format(domain=domain), self._on_control),
        ]
        self._status_key = STATUS_KEY.format(domain=domain)
        self._publish_clock()
        self._thread.start()

    def expect(self, pid: int, label: str) -> None:
        """The launch started process ``pid``: the time waits for it to join."""
        with self._changed:
            if not self._state.joined(pid):
                self._expected[pid] = (label, time.monotonic())
            self._notify()

    def launch_ready(self) -> None:
        """The launch has started every process it starts at once: the time may go."""
        with self._changed:
            self._started_all = True
            self._notify()

    def exited(self, pid: int) -> None:
        """Process ``pid`` exited: no longer a participant."""
        with self._changed:
            self._expected.pop(pid, None)
            self._state.forget_pid(pid)
            self._notify()

    def close(self) -> None:
        """Stop the thread and leave the transport."""
        with self._changed:
            self._stopped = True
            self._notify()
        if self._thread.is_alive():
            self._thread.join(timeout=2.0)
        self._context.try_shutdown()

    @property
    def time_ns(self) -> int:
        """The current simulated time."""
        return self._time_ns

    # the transport's threads ---------------------------------------------------------------
    def _on_report(self, sample: Any) -> None:
        try:
            report = Report.from_bytes(sample.payload.to_bytes())
        except ValueError:
            return
        if report.participant == self._stamp.id:
            return
        with self._changed:
            self._state.update(report)
            self._notify()

    def _on_control(self, sample: Any) -> None:
        try:
            request = json.loads(sample.payload.to_bytes())
            target = int(request["run_until_ns"])
        except (ValueError, KeyError, TypeError):
            return
        with self._changed:
            self._target_ns = max(target, self._target_ns or 0)
            self._notify()

    def _notify(self) -> None:
        """Something changed (call with ``_changed`` held): the loop looks again."""
        self._news = True
        self._changed.notify_all()

    # the decision loop ---------------------------------------------------------------------
    def _run(self) -> None:
        stalled_since = time.monotonic()
        noted = False
        last_resend = 0.0
        last_status: tuple[int, bool] | None = None
        while True:
            with self._changed:
                if not self._news:  # what came while the loop was busy counts too
                    self._changed.wait(timeout=0.2)
                self._news = False
                if self._stopped:
                    return
                self._give_up_on_late_joiners()
                reason = self._waiting_for()
                lagging = self._state.to_wake(self._time_ns)
            quiet = reason is None
            if self.options.paused and (self._time_ns, quiet) != last_status:
                last_status = (self._time_ns, quiet)
                self._publish_status(quiet)
            if not quiet:
                now = time.monotonic()
                if lagging and now - last_resend > _RESEND:
                    last_resend = now
                    self._wake(lagging)  # one that joined late, or a wake-up lost
                if not noted and now - stalled_since > _STALL_NOTE:
                    noted = True
                    self._log("WARNING", f"simulated time stands at {self._seconds()}: {reason}")
                continue
            if self._until_ns is not None and self._time_ns >= self._until_ns:
                self._log(
                    "INFO",
                    f"reached the simulated time {self._seconds()} in {self._steps} steps "
                    "(--until)",
                )
                self._on_until()
                self._until_ns = None
                continue
            next_ns = self._next_time()
            if next_ns is None:
                continue  # paused at the target
            if not self._pace(next_ns):
                return
            with self._changed:
                self._state.start_pairs(self._own_sent())
            self._time_ns = next_ns
            self._steps += 1
            self._stamp.advance_clocks(next_ns)
            if next_ns - self._clock_published_ns >= round(self.options.clock_period * _NS):
                self._publish_clock()
            with self._changed:
                due = self._state.to_wake(next_ns)
            self._wake(due)
            stalled_since, noted = time.monotonic(), False

    def _waiting_for(self) -> str | None:
        if not self._started_all:
            return "the launch is starting its processes"
        for pid, (label, _) in list(self._expected.items()):
            if self._state.joined(pid):
                del self._expected[pid]
            else:
                return f"{label} has not joined yet"
        return self._state.waiting_for(self._time_ns, self._own_sent(), self._own_matched())

    def _give_up_on_late_joiners(self) -> None:
        now = time.monotonic()
        for pid, (label, started) in list(self._expected.items()):
            if now - started > self.options.join_grace and not self._state.joined(pid):
                del self._expected[pid]
                self._log(
                    "WARNING",
                    f"{label} [pid {pid}] is outside the lockstep: it is not a launchkit node "
                    f"(or did not spin within {self.options.join_grace:g} s); the simulated "
                    "time does not wait for it",
                )

    def _next_time(self) -> int | None:
        """The time to advance to (None: hold, a test has not asked for more)."""
        limit = self._time_ns + round(self.options.max_step * _NS)
        candidates = [limit]
        due = self._state.next_due(self._time_ns)
        if due is not None:
            candidates.append(due)
        if self._until_ns is not None:
            candidates.append(max(self._until_ns, self._time_ns + 1))
        if self._target_ns is not None:
            if self._target_ns <= self._time_ns:
                return None
            candidates.append(self._target_ns)
        return min(candidates)

    def _pace(self, next_ns: int) -> bool:
        """Wait until ``next_ns`` may be published at the real-time factor; False if stopped."""
        if not self.options.rtf:
            return True
        now = time.monotonic()
        if self._pace_anchor is None or self._target_ns is not None:
            self._pace_anchor = (now, self._time_ns)
        wall, sim = self._pace_anchor
        due = wall + (next_ns - sim) / _NS / self.options.rtf
        if now - due > 0.25:  # far behind (a slow participant): keep the pace from here
            self._pace_anchor = (now, self._time_ns)
            return True
        with self._changed:
            while not self._stopped and time.monotonic() < due:
                self._changed.wait(timeout=due - time.monotonic())
            return not self._stopped

    # publishing ----------------------------------------------------------------------------
    def _own_sent(self) -> dict[str, tuple[str, int]]:
        pub = self._clock_pub
        return {} if pub is None else {pub.gid.hex(): (pub.topic_name, pub._sequence)}

    def _own_matched(self) -> dict[str, list[str]]:
        pub = self._clock_pub
        if pub is None:
            return {}
        tokens = self._context.graph.tokens("MS", pub.topic_name)
        return {pub.gid.hex(): [t.gid.hex() for t in tokens]}

    def _wake(self, participants: list[str]) -> None:
        """Tell ``participants`` the time reached their next due instant."""
        session, domain = self._context.session, self._context.domain_id
        for participant in participants:
            key = WAKE_KEY.format(domain=domain, participant=participant)
            session.put(key, str(self._time_ns).encode())

    def _publish_clock(self) -> None:
        """``/clock`` for every node: participants follow it (those with something due are
        woken directly), and so do the processes outside the lockstep."""
        self._clock_published_ns = self._time_ns
        sec, nanosec = divmod(self._time_ns, _NS)
        stamp = get_time_message(sec, nanosec)
        self._clock_pub.publish(self._clock_type(clock=stamp))

    def _publish_status(self, quiet: bool) -> None:
        status = {"time_ns": self._time_ns, "quiescent": quiet, "target_ns": self._target_ns}
        self._context.session.put(self._status_key, json.dumps(status).encode())

    def _seconds(self) -> str:
        return f"{self._time_ns / _NS:.3f} s"


def get_time_message(sec: int, nanosec: int) -> Any:
    """A ``builtin_interfaces/Time``."""
    from launchkit.ros.msgs import get_message

    return get_message("builtin_interfaces/msg/Time")(sec=sec, nanosec=nanosec)
