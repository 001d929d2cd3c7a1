"""Fixtures for the ROS layer's tests: child processes, contexts (on the ``router`` fixture's
private router)."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from ros_helpers import Child

from launchkit.ros.context import Context


@pytest.fixture
def children() -> Iterator[list[Child]]:
    """Start node processes with ``children.append(Child([...]))``; all are stopped after."""
    started: list[Child] = []
    try:
        yield started
    finally:
        for child in started:
            child.stop()


@pytest.fixture
def contexts(router: str) -> Iterator[Callable[..., Context]]:
    """Make initialized contexts (each its own Zenoh session, like separate processes), in the
    ROS domain given (``contexts(domain=0)``), else in ``$ROS_DOMAIN_ID``'s."""
    made: list[Context] = []

    def make(domain: int | None = None) -> Context:
        context = Context()
        context.init([], domain_id=domain)
        made.append(context)
        return context

    try:
        yield make
    finally:
        for context in made:
            context.try_shutdown()
