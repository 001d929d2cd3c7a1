"""Fixtures for the ROS layer's tests: a private router per test, child processes, contexts."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from ros_helpers import Child, free_port

from launchkit.ros.context import Context
from launchkit.ros.router import RouterHandle, start_router


@pytest.fixture
def router_endpoint(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A router hosted by the test process on a free loopback port; children are told of it."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    handle: RouterHandle = start_router(endpoint)
    assert handle.hosted
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    try:
        yield endpoint
    finally:
        handle.close()


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
def contexts(router_endpoint: str) -> Iterator[Callable[[], Context]]:
    """Make initialized contexts (each its own Zenoh session, like separate processes)."""
    made: list[Context] = []

    def make() -> Context:
        context = Context()
        context.init([])
        made.append(context)
        return context

    try:
        yield make
    finally:
        for context in made:
            context.try_shutdown()
