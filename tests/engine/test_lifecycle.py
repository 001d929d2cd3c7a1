"""The process lifecycle state machine, from scripted event histories (no processes, no clock:
each event carries the time it happens at)."""

from __future__ import annotations

import signal
from collections.abc import Sequence
from typing import Any

import pytest

from launchkit.runtime.lifecycle import (
    Escalation,
    ExitOutcome,
    Lifecycle,
    Respawn,
    RespawnPolicy,
    SendSignal,
    State,
    escalate_until_exited,
)

SIGINT, SIGTERM, SIGKILL = signal.SIGINT, signal.SIGTERM, signal.SIGKILL
ROS = Escalation.ros(sigterm_timeout=5.0, sigkill_timeout=2.0)

#: (time, event, argument): events are the Lifecycle's methods; "due" asks what is due.
History = Sequence[tuple[float, str, Any]]


def play(lifecycle: Lifecycle, history: History) -> list[tuple[float, object, State]]:
    """Feed ``history`` to ``lifecycle``; what each event returned and the state after it."""
    seen: list[tuple[float, object, State]] = []
    for now, event, argument in history:
        if event == "started":
            result: object = lifecycle.started()
        elif event == "exited":
            code, allowed = argument if isinstance(argument, tuple) else (argument, True)
            result = lifecycle.exited(code, now, respawn_allowed=allowed)
        elif event == "stop":
            result = lifecycle.stop(now, retire=bool(argument))
        else:
            result = getattr(lifecycle, event)(now)
        seen.append((now, result, lifecycle.state))
    return seen


def test_a_clean_run_ends_exited_without_respawn() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=False))
    assert play(lifecycle, [(0, "started", None), (3, "exited", 0), (9, "due", None)]) == [
        (0, None, State.RUNNING),
        (3, ExitOutcome(0, expected=False), State.EXITED),
        (9, None, State.EXITED),
    ]
    assert lifecycle.deadline is None


def test_respawn_waits_its_delay_and_gives_up_after_max_retries() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=1.5, max_retries=2))
    seen = play(
        lifecycle,
        [
            (0.0, "started", None),
            (1.0, "exited", 3),
            (2.4, "due", None),  # 0.1 s early: nothing
            (2.5, "due", None),
            (2.5, "started", None),
            (4.0, "exited", 3),
            (5.5, "due", None),
            (5.5, "started", None),
            (6.0, "exited", 3),
            (99.0, "due", None),
        ],
    )
    assert [result for _, result, _ in seen] == [
        None,
        ExitOutcome(3, expected=False, respawn_in=1.5),
        None,
        Respawn(),
        None,
        ExitOutcome(3, expected=False, respawn_in=1.5),
        Respawn(),
        None,
        ExitOutcome(3, expected=False, gave_up_after=2),
        None,
    ]
    assert [state for _, _, state in seen][1:3] == [State.BACKOFF, State.BACKOFF]
    assert lifecycle.state is State.EXITED and lifecycle.retries == 2


def test_unlimited_retries_never_give_up() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=0.0, max_retries=-1))
    for round_ in range(50):
        lifecycle.started()
        assert lifecycle.exited(1, float(round_)).respawn_in == 0.0
        assert lifecycle.due(float(round_)) == Respawn()
    assert lifecycle.retries == 50


def test_a_stop_escalates_sigint_sigterm_sigkill_on_its_deadlines() -> None:
    lifecycle = Lifecycle(ROS)
    seen = play(
        lifecycle,
        [
            (10.0, "started", None),
            (20.0, "stop", False),
            (24.9, "due", None),
            (25.0, "due", None),
            (26.9, "due", None),
            (27.0, "due", None),
            (40.0, "due", None),  # nothing after SIGKILL
            (40.1, "exited", -9),
        ],
    )
    assert [result for _, result, _ in seen] == [
        None,
        SendSignal(SIGINT),
        None,
        SendSignal(SIGTERM, escalated_from=SIGINT, waited=5.0),
        None,
        SendSignal(SIGKILL, escalated_from=SIGTERM, waited=2.0),
        None,
        ExitOutcome(-9, expected=True),
    ]
    assert lifecycle.signals == [SIGINT, SIGTERM, SIGKILL]


def test_an_exit_by_a_signal_we_did_not_send_is_a_death() -> None:
    lifecycle = Lifecycle(ROS)
    play(lifecycle, [(0, "started", None), (1, "stop", False)])
    assert lifecycle.exited(-signal.SIGSEGV, 2.0) == ExitOutcome(-signal.SIGSEGV, expected=False)
    lifecycle.started()
    assert lifecycle.exited(-signal.SIGINT, 3.0).expected is False  # running: not stopped by us


def test_stopping_during_backoff_cancels_the_respawn() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=5.0))
    seen = play(
        lifecycle, [(0, "started", None), (1, "exited", 2), (2, "stop", False), (9, "due", None)]
    )
    assert seen[2] == (2, None, State.EXITED)
    assert seen[3] == (9, None, State.EXITED)


def test_a_retired_process_is_never_respawned() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=0.0))
    seen = play(lifecycle, [(0, "started", None), (1, "stop", True), (2, "exited", -2)])
    assert seen[1][1] == SendSignal(SIGINT)
    assert seen[2] == (2, ExitOutcome(-2, expected=True), State.EXITED)
    lifecycle.started()
    assert lifecycle.exited(1, 3.0) == ExitOutcome(1, expected=False)


def test_no_respawn_while_the_launch_shuts_down() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True))
    lifecycle.started()
    assert lifecycle.exited(1, 0.0, respawn_allowed=False) == ExitOutcome(1, expected=False)
    assert lifecycle.state is State.EXITED


def test_escalate_skips_the_wait_and_stops_after_sigkill() -> None:
    lifecycle = Lifecycle(ROS)
    lifecycle.started()
    assert lifecycle.escalate(0.0) == SendSignal(SIGTERM)  # nothing sent yet: after SIGINT
    assert lifecycle.deadline == 2.0
    assert lifecycle.escalate(0.5) == SendSignal(SIGKILL)
    assert lifecycle.escalate(0.6) is None and lifecycle.deadline is None


def test_a_failed_start_is_final() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True))
    lifecycle.failed()
    assert lifecycle.state is State.FAILED and not lifecycle.alive
    assert lifecycle.stop(0.0) is None and lifecycle.due(100.0) is None


def test_another_ladder_sigterm_then_sigkill() -> None:
    ladder = Escalation(((SIGTERM, 3.0), (SIGKILL, None)))
    lifecycle = Lifecycle(ladder, RespawnPolicy(enabled=True, delay=1.0))
    lifecycle.started()
    assert lifecycle.stop(0.0, retire=True) == SendSignal(SIGTERM)
    assert lifecycle.due(3.0) == SendSignal(SIGKILL, escalated_from=SIGTERM, waited=3.0)
    assert ladder.after(SIGKILL) is None and ladder.after(SIGINT) is None


@pytest.mark.parametrize(
    ("exits_after", "expected"),
    [(0, [SIGINT]), (1, [SIGINT, SIGTERM]), (2, [SIGINT, SIGTERM, SIGKILL])],
)
def test_escalate_until_exited_stops_at_the_first_signal_that_works(
    exits_after: int, expected: list[signal.Signals]
) -> None:
    sent: list[signal.Signals] = []
    waits: list[float | None] = []

    def wait_exit(seconds: float | None) -> bool:
        waits.append(seconds)
        return len(sent) > exits_after or seconds is None

    assert escalate_until_exited(ROS, sent.append, wait_exit) == expected
    assert sent == expected
    assert waits == [5.0, 2.0, None][: len(expected)]


def test_quick_exits_back_off_doubling_up_to_the_maximum() -> None:
    # ROS respawns a program that fails at once in a busy loop (~825 starts a second)
    policy = RespawnPolicy(enabled=True, delay=0.0, backoff_first=0.1, backoff_max=1.0)
    lifecycle = Lifecycle(ROS, policy)
    now, waits = 0.0, []
    for _ in range(6):
        lifecycle.started(now)
        outcome = lifecycle.exited(1, now + 0.01)
        assert outcome.respawn_in is not None
        waits.append(outcome.respawn_in)
        now = lifecycle.deadline or 0.0
        assert lifecycle.due(now) == Respawn()
    assert waits == [0.1, 0.2, 0.4, 0.8, 1.0, 1.0]
    assert lifecycle.quick_exits == 6


def test_a_long_run_resets_the_backoff_and_a_longer_delay_wins() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=0.5, quick_exit=1.0))
    lifecycle.started(0.0)
    assert lifecycle.exited(1, 0.1).respawn_in == 0.5  # 0.1 s of backoff < the delay
    lifecycle.started(1.0)
    assert lifecycle.exited(1, 1.1).respawn_in == 0.5
    lifecycle.started(2.0)
    assert lifecycle.exited(1, 2.2).respawn_in == 0.5
    lifecycle.started(3.0)
    assert lifecycle.exited(1, 3.1).respawn_in == 0.8  # fourth quick exit: 0.1 * 2**3
    lifecycle.started(4.0)
    outcome = lifecycle.exited(1, 9.0)  # ran 5 s: not a quick exit
    assert (outcome.respawn_in, outcome.quick_exits) == (0.5, 0)


def test_without_a_start_time_there_is_no_backoff() -> None:
    lifecycle = Lifecycle(ROS, RespawnPolicy(enabled=True, delay=0.0))
    for now in (0.0, 0.01, 0.02):
        lifecycle.started()
        assert lifecycle.exited(1, now).respawn_in == 0.0
