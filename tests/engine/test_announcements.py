"""Announcements (the viewer's address) wait for the console to settle, then stand out: the rule
on a scripted clock; tests/engine/test_child_requests.py checks it with a real launcher."""

from __future__ import annotations

import io

from launchkit.runtime.announcements import LATEST, SETTLE, Announcements
from launchkit.runtime.output import Output

VIEWER = "viewer: http://127.0.0.1:8765/"


def console(colour: bool) -> tuple[Output, io.StringIO, Announcements]:
    """An output to a string, with or without a terminal's colours, and its announcements."""
    screen = io.StringIO()
    output = Output(screen, colour=colour)
    return output, screen, Announcements(output)


def test_an_announcement_waits_until_the_console_has_been_quiet() -> None:
    output, screen, held = console(colour=False)
    held.hold("rviz2-4", VIEWER, now=10.0)
    assert held.deadline() == 10.0 + SETTLE
    output.child_lines("gzserver-1", 1, ["spawned"], "screen", "stdout")
    held.print_due(10.5, shutting_down=False)  # output meanwhile: wait again from now
    assert held.deadline() == 10.5 + SETTLE
    held.print_due(10.5 + SETTLE - 0.01, shutting_down=False)
    assert VIEWER not in screen.getvalue()
    held.print_due(10.5 + SETTLE, shutting_down=False)
    assert screen.getvalue().splitlines()[-1] == f"[INFO] [rviz2-4]: {VIEWER}"  # plain: no TTY
    assert held.deadline() is None


def test_a_console_that_never_settles_gets_it_at_the_latest() -> None:
    output, screen, held = console(colour=False)
    held.hold("rviz2-4", VIEWER, now=0.0)
    now, step = 0.0, SETTLE / 2
    while VIEWER not in screen.getvalue():
        now += step
        assert now < LATEST + step, "never printed"
        output.child_lines("chatty-1", 1, ["still talking"], "screen", "stdout")
        held.print_due(now, shutting_down=False)
    assert now >= LATEST


def test_on_a_terminal_it_is_bold() -> None:
    _, screen, held = console(colour=True)
    held.hold("rviz2-4", VIEWER, now=0.0)
    held.print_due(SETTLE, shutting_down=False)
    assert screen.getvalue() == f"\033[1m[INFO] [rviz2-4]: {VIEWER}\033[0m\n"


def test_a_launch_shutting_down_drops_it() -> None:
    _, screen, held = console(colour=False)
    held.hold("rviz2-4", VIEWER, now=0.0)
    held.print_due(0.1, shutting_down=True)
    assert held.deadline() is None
    held.print_due(LATEST, shutting_down=False)
    assert screen.getvalue() == ""
