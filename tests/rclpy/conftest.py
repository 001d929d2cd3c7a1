"""Fixtures of the rclpy tests: each test gets a router of its own for launchkit's runs."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from rclpy_runs import Runs

from launchkit.ros.router import start_router
from launchkit.testing._isolation import free_loopback_port, router_endpoint


@pytest.fixture
def runs() -> Iterator[Callable[[str], Runs]]:
    """``runs(flavour)``: node files run on that rclpy; all stopped after the test."""
    endpoint = router_endpoint(free_loopback_port())
    router = start_router(endpoint)
    made: list[Runs] = []

    def make(flavour: str) -> Runs:
        made.append(Runs(flavour, endpoint))
        return made[-1]

    try:
        yield make
    finally:
        for each in made:
            each.close()
        router.close()
