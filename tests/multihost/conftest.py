"""Fixtures for the multi-host tests: two hosts (network namespaces) per test."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from netns import Hosts, netns_unavailable


@pytest.fixture(scope="session")
def netns_reason() -> str | None:
    """Why these tests cannot run here, if they cannot."""
    return netns_unavailable()


@pytest.fixture
def hosts(netns_reason: str | None) -> Iterator[Hosts]:
    """Hosts ``a`` and ``b`` on one link, removed after the test whatever happened."""
    if netns_reason is not None:
        pytest.skip(netns_reason)
    made = Hosts()
    try:
        yield made
    finally:
        made.close()
