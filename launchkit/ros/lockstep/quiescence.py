"""The rule that lets simulated time move on: every participant idle, every message handled.

Pure bookkeeping over the participants' latest :class:`~.report.Report`s, so it is tested
without processes. The authority may advance from ``T`` when:

1. every process it expects (started by the launch) has joined, or has been given up on;
2. every participant's latest report is idle, and at ``T`` if it had something due by then
   (a participant with nothing due is not woken: it follows the time when a message of a later
   instant reaches it, or ``/clock``);
3. every message sent so far on a topic has been handled by every participant subscription
   to that topic, counted by publisher sequence numbers: for a publisher ``P`` and a
   subscription ``S`` on its topic, ``S``'s last handled sequence number of ``P`` has reached
   ``P``'s last sent one.

Why this is enough: suppose all three hold on the latest reports, yet some participant is
busy. What woke it after its idle report was a message (a timer cannot fire while the time
stands still), sent either before the sender's latest report, and then rule 3 would fail
since the receiver's report predates handling it, or after it, and then the sender too was
busy after its report. Following senders back through strictly earlier events must end at a
first activity with no cause: there is none, so no participant is busy.

A new subscription holds the time until every publisher on its topic has discovered it
(its liveliness token, declared after the subscriber, has reached the publisher's process), so
no message of a later instant can miss it. A pair ``(P, S)`` counts from the step after both
were first reported: what ``P`` sent before may have been sent before ``S`` existed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from launchkit.ros.lockstep.report import Matched, Report, Sent


@dataclass
class Quiescence:
    """The participants' latest reports and the pairs they have been matched in."""

    reports: dict[str, Report] = field(default_factory=dict)
    #: (subscription GID, publisher GID) -> the publisher's sequence when the pair started
    baselines: dict[tuple[str, str], int] = field(default_factory=dict)

    def update(self, report: Report) -> None:
        """Keep ``report`` as its participant's latest (a leaving one removes it)."""
        if report.leaving:
            self.reports.pop(report.participant, None)
        else:
            self.reports[report.participant] = report

    def forget_pid(self, pid: int) -> list[str]:
        """Drop the participants of a process that exited; their names."""
        gone = [r for r in self.reports.values() if r.pids and r.pids[0] == pid]
        for report in gone:
            del self.reports[report.participant]
        return [r.name for r in gone]

    def joined(self, pid: int) -> bool:
        """Whether a participant of process ``pid`` (or of a child of it) has reported."""
        return any(pid in r.pids for r in self.reports.values())

    def publishers(self, extra_sent: Sent) -> dict[str, list[tuple[str, int]]]:
        """Every participant's publishers and ``extra_sent`` (the authority's own), by topic:
        (GID, last sequence number sent)."""
        by_topic: dict[str, list[tuple[str, int]]] = {}
        for sent in [*(r.sent for r in self.reports.values()), extra_sent]:
            for gid, (topic, seq) in sent.items():
                by_topic.setdefault(topic, []).append((gid, seq))
        return by_topic

    def waiting_for(self, time_ns: int, extra_sent: Sent, extra_matched: Matched) -> str | None:
        """What keeps the time at ``time_ns`` (None: it may advance). ``extra_sent`` and
        ``extra_matched`` add the authority's own publishers (``/clock``)."""
        for report in self.reports.values():
            if report.time_ns < time_ns and self.due(report, time_ns):
                return f"{report.name} has not reached the time yet"
            if not report.idle:
                return f"{report.name} is busy"
        by_topic = self.publishers(extra_sent)
        matched: dict[str, set[str]] = {gid: set(subs) for gid, subs in extra_matched.items()}
        for report in self.reports.values():
            matched.update((gid, set(subs)) for gid, subs in report.matched.items())
        for report in self.reports.values():
            for sub_gid, (topic, handled) in report.handled.items():
                for pub_gid, seq in by_topic.get(topic, ()):
                    if sub_gid not in matched.get(pub_gid, ()):
                        return f"a publisher of {topic} has not discovered {report.name} yet"
                    baseline = self.baselines.get((sub_gid, pub_gid))
                    if baseline is not None and seq > baseline and handled.get(pub_gid, 0) < seq:
                        return f"{report.name} has not handled every message on {topic}"
        return None

    @staticmethod
    def due(report: Report, time_ns: int) -> bool:
        """Whether ``report``'s participant has something due at or before ``time_ns``."""
        return report.next_ns is not None and report.next_ns <= time_ns

    def to_wake(self, time_ns: int) -> list[str]:
        """The participants with something due at ``time_ns`` that have not reached it."""
        return [
            r.participant
            for r in self.reports.values()
            if r.time_ns < time_ns and self.due(r, time_ns)
        ]

    def next_due(self, after_ns: int) -> int | None:
        """The earliest time after ``after_ns`` that a participant has something due."""
        due = [r.next_ns for r in self.reports.values() if r.next_ns is not None]
        later = [t for t in due if t > after_ns]
        return min(later) if later else None

    def start_pairs(self, extra_sent: Sent) -> None:
        """At an advance: count from now every (publisher, subscription) pair on one topic
        not counted yet."""
        by_topic = self.publishers(extra_sent)
        for report in self.reports.values():
            for sub_gid, (topic, _) in report.handled.items():
                for pub_gid, seq in by_topic.get(topic, ()):
                    self.baselines.setdefault((sub_gid, pub_gid), seq)
