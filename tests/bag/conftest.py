"""Fixtures of the bag tests: a router hosted by the test process on a free loopback port."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from launchkit.ros.router import start_router
from tests.bag.helpers import free_port


@pytest.fixture
def router(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A router on a free loopback port, announced to children through LAUNCHKIT_ROUTER."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    handle = start_router(endpoint)
    assert handle.hosted
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    try:
        yield endpoint
    finally:
        handle.close()
