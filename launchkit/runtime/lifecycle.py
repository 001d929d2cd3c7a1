"""The life of one supervised process, as a pure state machine (supervisor/circus style).

::

    STARTING ─started─▶ RUNNING ─exited─▶ EXITED ─(respawn policy)─▶ BACKOFF ─due─▶ (respawn)
        │                  │                                            │
        └─failed─▶ FAILED  └─stop─▶ STOPPING ─exited─▶ EXITED           └─stop─▶ EXITED
                                     │    ▲
                                     └────┘ due or escalate: the next signal of the ladder
                                            (SIGINT ─sigterm_timeout─▶ SIGTERM
                                             ─sigkill_timeout─▶ SIGKILL for a launch's processes)

A respawn waits ``respawn_delay`` seconds, as ROS's; an incarnation that exits within
:attr:`RespawnPolicy.quick_exit` seconds of its start makes the next respawn wait longer, doubling
from :attr:`RespawnPolicy.backoff_first` up to :attr:`RespawnPolicy.backoff_max` while the quick
exits go on (ROS respawns a program that fails at once in a busy loop).

Nothing here touches a process, a clock or a signal. Every event comes with the time it
happened, every decision comes back as an effect (:class:`SendSignal`, :class:`Respawn`) or an
:class:`ExitOutcome` for the caller to carry out and report, and :attr:`Lifecycle.deadline` says
when :meth:`Lifecycle.due` must be called next. The launcher's supervisor
(:mod:`launchkit.runtime.supervisor`), the simulator's fallback supervision of its plugin nodes
and the test plugin's stop of a launch are loops around it; it is unit-tested from scripted
event histories (``tests/engine/test_lifecycle.py``).
"""

from __future__ import annotations

import enum
import signal
from collections.abc import Callable
from dataclasses import dataclass


class State(enum.Enum):
    """Where a process is in its lifecycle."""

    STARTING = "starting"
    RUNNING = "running"
    STOPPING = "stopping"
    BACKOFF = "backoff"
    EXITED = "exited"
    FAILED = "failed"


@dataclass(frozen=True)
class Escalation:
    """The signals that stop a process, in order, each with how many seconds it gets before
    the next one is sent (None for the last: nothing comes after it)."""

    steps: tuple[tuple[signal.Signals, float | None], ...]

    @classmethod
    def ros(cls, sigterm_timeout: float, sigkill_timeout: float) -> Escalation:
        """ROS's ladder for a launch's processes: SIGINT, then SIGTERM, then SIGKILL."""
        return cls(
            (
                (signal.SIGINT, sigterm_timeout),
                (signal.SIGTERM, sigkill_timeout),
                (signal.SIGKILL, None),
            )
        )

    def first(self) -> signal.Signals:
        """The signal a stop begins with."""
        return self.steps[0][0]

    def grace(self, signum: signal.Signals) -> float | None:
        """Seconds ``signum`` gets before the next signal (None: no next signal)."""
        for step, seconds in self.steps:
            if step == signum:
                return seconds
        return None

    def after(self, signum: signal.Signals) -> signal.Signals | None:
        """The signal that follows ``signum`` on the ladder, if any."""
        signals = [step for step, _ in self.steps]
        if signum not in signals:
            return None
        index = signals.index(signum) + 1
        return signals[index] if index < len(signals) else None


@dataclass(frozen=True)
class RespawnPolicy:
    """Whether a process that exits on its own is started again: after ``delay`` seconds, at
    most ``max_retries`` times (negative: without limit), as ROS's ``respawn`` attributes.

    An incarnation that ran less than ``quick_exit`` seconds failed quickly: the k-th such
    exit in a row waits at least ``backoff_first * 2**(k-1)`` seconds, at most ``backoff_max``."""

    enabled: bool = False
    delay: float = 0.0
    max_retries: int = -1
    quick_exit: float = 1.0
    backoff_first: float = 0.1
    backoff_max: float = 10.0

    def wait(self, quick_exits: int) -> float:
        """Seconds before the next start after ``quick_exits`` quick exits in a row."""
        if quick_exits <= 0:
            return self.delay
        backoff = min(self.backoff_max, self.backoff_first * 2.0 ** min(quick_exits - 1, 60))
        return max(self.delay, backoff)


@dataclass(frozen=True)
class SendSignal:
    """Effect: send ``signum`` to the process (its whole group). When it escalates,
    ``escalated_from`` is the signal that did not stop the process in ``waited`` seconds."""

    signum: signal.Signals
    escalated_from: signal.Signals | None = None
    waited: float = 0.0


@dataclass(frozen=True)
class Respawn:
    """Effect: start a new incarnation of the process now (its backoff is over)."""


@dataclass(frozen=True)
class ExitOutcome:
    """What an exit means: ``expected`` when a signal we sent ended it; ``respawn_in`` seconds
    when a respawn is scheduled (``quick_exits``: how many exits in a row came soon after their
    start, which lengthens the wait); ``gave_up_after`` retries when the policy's limit is
    reached."""

    code: int
    expected: bool
    respawn_in: float | None = None
    gave_up_after: int | None = None
    quick_exits: int = 0


class Lifecycle:
    """One process's state, its respawn count and its pending deadline."""

    def __init__(self, escalation: Escalation, respawn: RespawnPolicy | None = None) -> None:
        self.escalation = escalation
        self.respawn = respawn or RespawnPolicy()
        self.state = State.STARTING
        self.retries = 0
        self.retired = False  # stopped on request (not by a shutdown): never respawned
        self.returncode: int | None = None
        self.signals: list[signal.Signals] = []  # sent to the current incarnation
        self.deadline: float | None = None  # when due() has something to do
        self.started_at: float | None = None  # when the current incarnation started
        self.quick_exits = 0  # exits in a row within respawn.quick_exit of their start

    @property
    def alive(self) -> bool:
        """Whether an incarnation is running (or being stopped)."""
        return self.state in (State.RUNNING, State.STOPPING)

    # -- events --------------------------------------------------------------------------------

    def started(self, now: float | None = None) -> None:
        """A new incarnation is running (since ``now``, when known: a quick exit is seen only
        then)."""
        self.state = State.RUNNING
        self.returncode = None
        self.signals.clear()
        self.deadline = None
        self.started_at = now

    def failed(self) -> None:
        """The process could not be started."""
        self.state = State.FAILED
        self.deadline = None

    def exited(self, code: int, now: float, *, respawn_allowed: bool = True) -> ExitOutcome:
        """The incarnation exited with ``code`` (negative: killed by that signal).
        ``respawn_allowed`` is false while the launch shuts down or when the exit ends it."""
        stopping = self.state is State.STOPPING
        expected = stopping and code < 0 and -code in self.signals
        self.returncode = code
        self.state = State.EXITED
        self.deadline = None
        policy = self.respawn
        quick = self.started_at is not None and now - self.started_at < policy.quick_exit
        self.quick_exits = self.quick_exits + 1 if quick else 0
        if not (respawn_allowed and policy.enabled) or self.retired or stopping:
            return ExitOutcome(code, expected)
        if 0 <= policy.max_retries <= self.retries:
            return ExitOutcome(code, expected, gave_up_after=policy.max_retries)
        self.retries += 1
        self.state = State.BACKOFF
        wait = policy.wait(self.quick_exits)
        self.deadline = now + wait
        return ExitOutcome(code, expected, respawn_in=wait, quick_exits=self.quick_exits)

    def stop(self, now: float, *, retire: bool = False) -> SendSignal | None:
        """Stop the process: the first signal of the ladder if it runs, nothing if it is
        waiting to respawn (the respawn is cancelled). ``retire``: never respawn it again."""
        self.retired = self.retired or retire
        if self.state is State.BACKOFF:
            self.state = State.EXITED
            self.deadline = None
            return None
        if self.state is not State.RUNNING:
            return None
        return self._send(self.escalation.first(), now)

    def escalate(self, now: float) -> SendSignal | None:
        """Send the next signal of the ladder now, without waiting (the user insists)."""
        last = self.signals[-1] if self.signals else self.escalation.first()
        following = self.escalation.after(last)
        if following is None:
            self.deadline = None
            return None
        return self._send(following, now)

    def due(self, now: float) -> SendSignal | Respawn | None:
        """What to do at ``now``: escalate a stop that took too long, or end a backoff."""
        if self.deadline is None or now < self.deadline:
            return None
        if self.state is State.BACKOFF:
            self.deadline = None
            return Respawn()
        if self.state is not State.STOPPING or not self.signals:
            self.deadline = None
            return None
        last = self.signals[-1]
        following = self.escalation.after(last)
        if following is None:
            self.deadline = None
            return None
        effect = self._send(following, now)
        return SendSignal(effect.signum, last, self.escalation.grace(last) or 0.0)

    def _send(self, signum: signal.Signals, now: float) -> SendSignal:
        self.signals.append(signum)
        self.state = State.STOPPING
        grace = self.escalation.grace(signum)
        self.deadline = None if grace is None else now + grace
        return SendSignal(signum)


def escalate_until_exited(
    escalation: Escalation,
    send: Callable[[signal.Signals], None],
    wait_exit: Callable[[float | None], bool],
) -> list[signal.Signals]:
    """Stop one process from a thread that may block: send each signal of ``escalation`` in
    turn until ``wait_exit(seconds)`` (None: as long as it takes) reports the process gone.
    Returns the signals sent."""
    sent: list[signal.Signals] = []
    for signum, grace in escalation.steps:
        send(signum)
        sent.append(signum)
        if wait_exit(grace):
            break
    return sent
