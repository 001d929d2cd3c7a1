"""Helpers shared by tests of several folders: a router hosted by the test process, and a
poll with a deadline for conditions that no event announces.

(``launchkit.testing._isolation`` has the free loopback port and the router endpoint for it.)
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

from launchkit.testing._isolation import free_loopback_port, router_endpoint


@contextmanager
def hosted_router() -> Iterator[str]:
    """A Zenoh router hosted by this process on a free loopback port; its endpoint."""
    from launchkit.ros.router import start_router  # zenoh: only for the tests that need it

    endpoint = router_endpoint(free_loopback_port())
    handle = start_router(endpoint)
    assert handle.hosted, f"another router already listens at {endpoint}"
    try:
        yield endpoint
    finally:
        handle.close()


def wait_until(
    predicate: Callable[[], bool], timeout: float, what: str, *, every: float = 0.02
) -> None:
    """Poll ``predicate`` every ``every`` seconds until it holds; fail naming ``what`` after
    ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(every)
