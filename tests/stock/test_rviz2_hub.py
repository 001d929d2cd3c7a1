"""The hub's measured topic rates (launchkit/stock/rviz2/hub.py); the rest of the hub is tested
through the rviz2 process in test_rviz2_server.py."""

from __future__ import annotations

import pytest

from launchkit.stock.rviz2.hub import RateMeter


def test_a_topic_rate_is_measured_from_the_intervals_in_the_window() -> None:
    meter = RateMeter()
    for i in range(11):
        meter.tick(100.0 + i * 0.1)  # 10 Hz for a second
    assert meter.rate(101.05) == pytest.approx(10.0)
    assert meter.rate(103.5) == 0.0  # nothing for longer than the window
