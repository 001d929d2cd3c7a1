"""A process's side of the lockstep: count what it sends and handles, say when it is idle.

One :class:`Participant` per ROS context (``Context.lockstep``), made when the process runs
with ``LAUNCHKIT_LOCKSTEP=1`` (the test plugin makes one for its own node). Publishers stamp
their messages' attachments with the simulated time instead of the wall time; subscriptions
count, per publisher, the last sequence number handled (taken by a callback, or pushed out of
a full queue: either way nothing of it is left to do); executors call :meth:`on_idle` when
they find nothing to run, and the participant then sends a :class:`~.report.Report` if its
state changed since the last one.

A message stamped with a simulated time the participant has not seen yet moves its nodes'
clocks there before the message is queued: the authority publishes that time before anything
can be stamped with it, so this only saves a race with ``/clock`` (a timer due at that instant
then runs before the message's callback, whichever of the two arrived first).
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections.abc import Iterator
from typing import Any

from launchkit.envvars import LOCKSTEP
from launchkit.ros.keyexpr import decode_attachment
from launchkit.ros.lockstep.report import REPORT_KEY, WAKE_KEY, Handled, Matched, Report, Sent

#: Wall seconds after which an idle participant says the same again (an authority that
#: started listening late, or a report lost).
HEARTBEAT = 1.0
#: Attachment stamps below this (2001-09-09 as epoch nanoseconds) are simulated times; a
#: process outside the lockstep stamps wall time, far above it, and does not move clocks.
SIM_TIME_LIMIT_NS = 10**18


def stamp_ns(context: Any) -> int:
    """What a message of ``context`` carries as its source time: the simulated time in a
    lockstep launch, the wall time otherwise (rmw_zenoh's)."""
    lockstep = context.lockstep
    return time.time_ns() if lockstep is None else int(lockstep.time_ns)


def holding(context: Any) -> contextlib.AbstractContextManager[None]:
    """``with holding(context):`` keeps a lockstep launch's simulated time where it is while
    the block runs (:meth:`Participant.hold`); nothing outside a lockstep launch."""
    lockstep = context.lockstep
    return contextlib.nullcontext() if lockstep is None else lockstep.hold()


def wanted() -> bool:
    """Whether this process runs in a lockstep launch (``LAUNCHKIT_LOCKSTEP=1``)."""
    return os.environ.get(LOCKSTEP) == "1"


class Participant:
    """One context's part in the lockstep (see the module's docstring)."""

    def __init__(self, context: Any, name: str = "") -> None:
        # context: a launchkit.ros.context.Context (which imports this module)
        self.context = context
        self.name = name or os.path.basename(context.argv[0] if context.argv else "python")
        self.id = f"{os.getpid()}-{id(self):x}"
        self._time_ns = 0
        self._handled: dict[int, tuple[str, str, dict[str, int]]] = {}  # id(subscription) ->
        self._lock = threading.Lock()
        self._last: Report | None = None
        self._sent_at = 0.0
        self._watching_graph = False
        # the graph's subscriptions by topic, as of the graph's version _seen_version
        self._graph_version = 0
        self._seen_version = -1
        self._subscriptions_seen: dict[str, list[str]] = {}
        self._sleeps: dict[int, int] = {}  # thread id -> the simulated time it sleeps until
        self._woken: set[int] = set()  # threads woken by the clock, not sleeping or spinning
        self._holds = 0  # blocks of code that keep the time where it is (see hold)
        self._wake_sub: Any = None  # the authority's "your next instant is due" (see _send)
        context.on_shutdown(self.leave)

    # what publishers and subscriptions call ------------------------------------------------
    @property
    def time_ns(self) -> int:
        """The latest simulated time this participant has seen (what its messages carry)."""
        return self._time_ns

    def received(self, attachment: bytes | None) -> None:
        """A message arrived (a Zenoh thread): follow the simulated time it carries."""
        decoded = decode_attachment(attachment)
        if decoded is not None and self._time_ns < decoded.timestamp_ns < SIM_TIME_LIMIT_NS:
            self.advance_clocks(decoded.timestamp_ns)

    def advance_clocks(self, time_ns: int) -> None:
        """Move every simulated clock of the context's nodes forward to ``time_ns``."""
        with self._lock:
            if time_ns <= self._time_ns:
                return
            self._time_ns = time_ns
        for node in list(self.context._nodes):
            clock: Any = getattr(node, "get_clock", lambda: None)()  # a ROSClock
            if getattr(clock, "ros_time_is_active", False) and clock.now().nanoseconds < time_ns:
                clock._set_override_ns(time_ns)

    def handled(self, subscription: Any, attachment: bytes | None) -> None:
        """``subscription`` is done with the message of ``attachment`` (taken or dropped)."""
        decoded = decode_attachment(attachment)
        if decoded is None:
            return
        with self._lock:
            entry = self._handled.get(id(subscription))
            if entry is None:
                entry = (subscription.gid.hex(), subscription.topic_name, {})
                self._handled[id(subscription)] = entry
            seqs = entry[2]
            publisher = decoded.gid.hex()
            if decoded.sequence > seqs.get(publisher, 0):
                seqs[publisher] = decoded.sequence

    # what clocks call (launchkit.ros.clock.SleepWatcher) ------------------------------------
    def sleeping(self, until_ns: int) -> None:
        """The calling thread sleeps on the simulated clock until ``until_ns``."""
        me = threading.get_ident()
        with self._lock:
            self._woken.discard(me)
            self._sleeps[me] = until_ns
        self._wake_executors()  # the time now has something due: say so

    def woke(self) -> None:
        """The calling thread's sleep ended: it is busy until it sleeps or spins again."""
        me = threading.get_ident()
        with self._lock:
            self._sleeps.pop(me, None)
            self._woken.add(me)

    @contextlib.contextmanager
    def hold(self) -> Iterator[None]:
        """Keep the simulated time where it is while the block runs (waiting for a service,
        say: what the node does once it is there then happens at the same instant in every
        run). The block's own timeouts are wall time."""
        with self._lock:
            self._holds += 1
        self._send(self.report())
        try:
            yield
        finally:
            with self._lock:
                self._holds -= 1
            self._wake_executors()

    def _wake_executors(self) -> None:
        for node in list(self.context._nodes):
            node.wake()

    # what executors call ------------------------------------------------------------------
    def on_idle(self) -> None:
        """An executor found nothing to run: report the state if it changed."""
        with self._lock:
            self._woken.discard(threading.get_ident())  # this thread spins, so is not busy
        report = self.report()
        if report.same_state(self._last) and time.monotonic() - self._sent_at < HEARTBEAT:
            return
        self._send(report)

    def report(self, *, leaving: bool = False) -> Report:
        """This participant's state now."""
        now = self._time_ns
        sent: Sent = {}
        handled: Handled = {}
        idle = True
        next_ns: int | None = None
        subscriptions: set[int] = set()
        for node in list(self.context._nodes):
            for publisher in getattr(node, "publishers", ()):
                sent[publisher.gid.hex()] = (publisher.topic_name, publisher._sequence)
            for subscription in getattr(node, "subscriptions", ()):
                subscriptions.add(id(subscription))
                handled[subscription.gid.hex()] = (subscription.topic_name, {})
            work = getattr(node, "work", None)
            if work is not None and work.pending():
                idle = False
            if any(client.requests_in_flight() for client in getattr(node, "clients", ())):
                idle = False
            for timer in getattr(node, "timers", ()):
                remaining = timer.time_until_next_call()
                if remaining is None or not getattr(timer.clock, "ros_time_is_active", False):
                    continue
                due = timer.clock.now().nanoseconds + remaining
                if due <= now:
                    idle = False
                next_ns = due if next_ns is None else min(next_ns, due)
        with self._lock:
            if self._woken or self._holds:
                idle = False
            for due in self._sleeps.values():
                idle = idle and due > now
                next_ns = due if next_ns is None else min(next_ns, due)
            for key in [k for k in self._handled if k not in subscriptions]:
                del self._handled[key]  # destroyed subscriptions
            for gid, topic, seqs in self._handled.values():
                handled[gid] = (topic, dict(seqs))
        pids = (os.getpid(), os.getppid())
        matched = self._matched(sent) if sent else {}
        return Report(self.id, pids, self.name, now, idle, next_ns, sent, handled, matched, leaving)

    def _matched(self, sent: Sent) -> Matched:
        """Which subscriptions (by GID) each publisher's side has discovered."""
        graph = self.context.graph
        if not self._watching_graph:
            self._watching_graph = True
            graph.add_listener(self._graph_changed)
        version = self._graph_version
        by_topic = self._subscriptions_seen
        if self._seen_version != version:  # the graph's subscriptions changed since
            by_topic = {}
            for token in graph.tokens("MS"):
                by_topic.setdefault(token.topic, []).append(token.gid.hex())
            for subscriptions in by_topic.values():
                subscriptions.sort()
            self._subscriptions_seen, self._seen_version = by_topic, version
        return {gid: by_topic.get(topic, []) for gid, (topic, _) in sent.items()}

    def _graph_changed(self, token: Any, appeared: bool) -> None:
        # a Zenoh thread: a subscription appeared or left; the executors report it
        if token.kind == "MS":
            self._graph_version += 1
            self._wake_executors()

    def _send(self, report: Report) -> None:
        domain = self.context.domain_id
        self._last = report
        self._sent_at = time.monotonic()
        with contextlib.suppress(Exception):  # the session is closing: the launcher sees the exit
            session = self.context.session
            if self._wake_sub is None and not report.leaving:
                wake = WAKE_KEY.format(domain=domain, participant=self.id)
                self._wake_sub = session.declare_subscriber(wake, self._on_wake)
            session.put(REPORT_KEY.format(domain=domain, participant=self.id), report.to_bytes())

    def _on_wake(self, sample: Any) -> None:
        # a Zenoh thread: the time reached this participant's next due instant
        try:
            time_ns = int(sample.payload.to_bytes())
        except ValueError:
            return
        self.advance_clocks(time_ns)
        self._wake_executors()

    def leave(self) -> None:
        """Tell the authority this participant is gone (its context shuts down)."""
        self._send(self.report(leaving=True))
