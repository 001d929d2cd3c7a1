"""teleop_twist_keyboard's key map and speed controls, as the original behaves (no terminal)."""

from __future__ import annotations

import pytest

from launchkit.stock.teleop_twist_keyboard.keys import (
    BANNER,
    BANNER_EVERY,
    CTRL_C,
    Teleop,
    Velocity,
    speed_line,
)


def test_banner_and_first_status_line_match_the_seed() -> None:
    lines = Teleop().start_lines()
    assert lines[0] == BANNER
    for text in (
        "Moving around:\n   u    i    o\n   j    k    l\n   m    ,    .\n",
        "   M    <    >",
    ):
        assert text in BANNER
    assert "q/z : increase/decrease max speeds by 10%" in BANNER
    assert "CTRL-C to quit" in BANNER
    assert lines[1] == "currently:\tspeed 0.50\tturn 1.00 "


@pytest.mark.parametrize(
    ("key", "expected"),
    [
        ("i", Velocity(x=0.5)),
        ("o", Velocity(x=0.5, yaw=-1.0)),
        ("j", Velocity(yaw=1.0)),
        ("l", Velocity(yaw=-1.0)),
        ("u", Velocity(x=0.5, yaw=1.0)),
        (",", Velocity(x=-0.5)),
        (".", Velocity(x=-0.5, yaw=1.0)),
        ("m", Velocity(x=-0.5, yaw=-1.0)),
        ("I", Velocity(x=0.5)),
        ("J", Velocity(y=0.5)),
        ("L", Velocity(y=-0.5)),
        ("U", Velocity(x=0.5, y=0.5)),
        ("O", Velocity(x=0.5, y=-0.5)),
        ("M", Velocity(x=-0.5, y=0.5)),
        ("<", Velocity(x=-0.5)),
        (">", Velocity(x=-0.5, y=-0.5)),
        ("t", Velocity(z=0.5)),
        ("b", Velocity(z=-0.5)),
    ],
)
def test_move_keys(key: str, expected: Velocity) -> None:
    outcome = Teleop().press(key)
    assert outcome.velocity == expected
    assert outcome.lines == []
    assert not outcome.quit


@pytest.mark.parametrize("key", ["k", " ", "p", "\r"])
def test_any_other_key_stops(key: str) -> None:
    teleop = Teleop()
    teleop.press("u")
    outcome = teleop.press(key)
    assert outcome.velocity == Velocity()
    assert not outcome.quit


def test_ctrl_c_stops_and_quits() -> None:
    teleop = Teleop()
    teleop.press("i")
    outcome = teleop.press(CTRL_C)
    assert outcome.velocity == Velocity()
    assert outcome.quit


@pytest.mark.parametrize(
    ("key", "speed", "turn"),
    [
        ("q", 0.55, 1.1),
        ("z", 0.45, 0.9),
        ("w", 0.55, 1.0),
        ("x", 0.45, 1.0),
        ("e", 0.5, 1.1),
        ("c", 0.5, 0.9),
    ],
)
def test_speed_keys_scale_and_keep_the_direction(key: str, speed: float, turn: float) -> None:
    teleop = Teleop()
    teleop.press("u")
    outcome = teleop.press(key)
    assert (teleop.speed, teleop.turn) == pytest.approx((speed, turn))
    assert outcome.velocity.x == pytest.approx(speed)
    assert outcome.velocity.yaw == pytest.approx(turn)
    assert outcome.lines == [speed_line(teleop.speed, teleop.turn)]


def test_limits_cap_the_speeds_and_say_so() -> None:
    teleop = Teleop(speed=0.95, turn=0.5, speed_limit=1.0, turn_limit=10.0)
    outcome = teleop.press("q")
    assert teleop.speed == 1.0
    assert teleop.turn == pytest.approx(0.55)
    assert outcome.lines == ["Linear speed limit reached!", "currently:\tspeed 1.00\tturn 0.55 "]


def test_banner_repeats_every_fifteen_speed_changes() -> None:
    teleop = Teleop()
    shown = [BANNER in teleop.press("w" if n % 2 else "x").lines for n in range(2 * BANNER_EVERY)]
    assert [n for n, banner in enumerate(shown) if banner] == [
        BANNER_EVERY - 1,
        2 * BANNER_EVERY - 1,
    ]
