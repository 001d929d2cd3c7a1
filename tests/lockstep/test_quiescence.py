"""The rule that lets the lockstep clock advance, on scripted reports (no processes)."""

from __future__ import annotations

from launchkit.ros.lockstep.quiescence import Quiescence
from launchkit.ros.lockstep.report import Handled, Matched, Report, Sent

CLOCK = {"c10c": ("/clock", 3)}  # the authority's /clock publisher: GID -> (topic, last seq)
CLOCK_SEEN = {"c10c": ["sub-clock-a", "sub-clock-b"]}


def report(
    name: str,
    *,
    sent: Sent | None = None,
    matched: Matched | None = None,
    handled: Handled | None = None,
    next_ns: int | None = None,
) -> Report:
    """Participant ``name`` idle at 100 ns, having handled every /clock so far."""
    on_clock: Handled = {f"sub-clock-{name}": ("/clock", {"c10c": 3})}
    return Report(
        name,
        (1000 + ord(name),),
        name,
        100,
        True,
        next_ns,
        sent or {},
        {**on_clock, **(handled or {})},
        matched or {},
    )


def state(*reports: Report, started: bool = True) -> Quiescence:
    quiet = Quiescence()
    for r in reports:
        quiet.update(r)
    if started:
        quiet.start_pairs(CLOCK)
    return quiet


def test_every_participant_idle_at_the_time_with_every_message_handled_may_advance() -> None:
    a = report("a", sent={"pa": ("/chatter", 5)}, matched={"pa": ["sub-b"]})
    b = report("b", handled={"sub-b": ("/chatter", {"pa": 5})})
    assert state(a, b).waiting_for(100, CLOCK, CLOCK_SEEN) is None


def test_a_busy_participant_or_one_behind_the_time_holds_it() -> None:
    busy = Report("a", (1,), "a", 100, False)
    assert "a is busy" in str(state(busy).waiting_for(100, {}, {}))
    behind = Report("a", (1,), "a", 90, True, next_ns=95)
    assert state(Report("a", (1,), "a", 90, True, next_ns=150)).waiting_for(100, {}, {}) is None
    assert "a has not reached the time" in str(state(behind).waiting_for(100, {}, {}))


def test_a_message_sent_but_not_handled_holds_the_time() -> None:
    quiet = state(
        report("a", sent={"pa": ("/chatter", 5)}, matched={"pa": ["sub-b"]}),
        report("b", handled={"sub-b": ("/chatter", {"pa": 5})}),
    )
    # a sends a sixth message, reported before b has taken it
    quiet.update(report("a", sent={"pa": ("/chatter", 6)}, matched={"pa": ["sub-b"]}))
    assert "b has not handled every message on /chatter" in str(
        quiet.waiting_for(100, CLOCK, CLOCK_SEEN)
    )
    quiet.update(report("b", handled={"sub-b": ("/chatter", {"pa": 6})}))
    assert quiet.waiting_for(100, CLOCK, CLOCK_SEEN) is None


def test_a_subscription_its_publisher_has_not_discovered_holds_the_time() -> None:
    a = report("a", sent={"pa": ("/chatter", 5)}, matched={"pa": []})
    b = report("b", handled={"sub-b": ("/chatter", {})})
    assert "has not discovered b" in str(state(a, b).waiting_for(100, CLOCK, CLOCK_SEEN))


def test_messages_sent_before_a_pair_was_counted_are_not_awaited() -> None:
    # b subscribed after a had sent 5 messages it never saw: only later ones count
    a = report("a", sent={"pa": ("/chatter", 5)}, matched={"pa": ["sub-b"]})
    b = report("b", handled={"sub-b": ("/chatter", {})})
    quiet = state(a, b)
    assert quiet.waiting_for(100, CLOCK, CLOCK_SEEN) is None
    quiet.update(report("a", sent={"pa": ("/chatter", 6)}, matched={"pa": ["sub-b"]}))
    assert quiet.waiting_for(100, CLOCK, CLOCK_SEEN) is not None


def test_the_next_time_is_the_earliest_due_and_leavers_and_exits_are_forgotten() -> None:
    a = report("a", next_ns=350)
    b = report("b", next_ns=250)
    quiet = state(a, b)
    assert quiet.next_due(100) == 250
    quiet.update(Report("b", (1000 + ord("b"),), "b", 100, True, leaving=True))
    assert quiet.next_due(100) == 350
    assert quiet.joined(1000 + ord("a"))
    assert quiet.forget_pid(1000 + ord("a")) == ["a"]
    assert quiet.next_due(100) is None


def test_reports_survive_the_transport() -> None:
    original = report("a", sent={"pa": ("/x", 2)}, matched={"pa": ["s"]}, next_ns=7)
    assert Report.from_bytes(original.to_bytes()) == original
