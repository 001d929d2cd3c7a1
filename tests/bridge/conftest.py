"""Fixtures of the bridge's tests: one router, one DDS domain and one bridge per module."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from bridge_helpers import DDS_ENV, RCLPY_MISSING, BridgeProcess, DdsPeer, LaunchkitPeer

from launchkit.ros.router import start_router
from launchkit.testing._isolation import domain_id, free_loopback_port, router_endpoint


@pytest.fixture(scope="module")
def dds_domain() -> Iterator[int]:
    """This module's ROS domain, with DDS discovery kept on loopback (skips without rclpy)."""
    pytest.importorskip("rclpy", reason=RCLPY_MISSING, exc_type=ImportError)
    with pytest.MonkeyPatch.context() as patch:
        domain = domain_id()
        for name, value in DDS_ENV.items():
            patch.setenv(name, value)
        patch.setenv("ROS_DOMAIN_ID", str(domain))
        yield domain


@pytest.fixture(scope="module")
def router(dds_domain: int) -> Iterator[str]:
    """A launchkit router on a free loopback port."""
    endpoint = router_endpoint(free_loopback_port())
    handle = start_router(endpoint)
    assert handle.hosted
    yield endpoint
    handle.close()


@pytest.fixture(scope="module")
def bridge(router: str, dds_domain: int) -> Iterator[BridgeProcess]:
    """``launchkit bridge`` between the module's router and DDS domain."""
    process = BridgeProcess(router, dds_domain)
    process.wait_line("bridging ROS_DOMAIN_ID")
    yield process
    assert process.stop() == 0, "\n".join(process.lines[-30:])


@pytest.fixture(scope="module")
def dds(dds_domain: int) -> Iterator[DdsPeer]:
    """A real rclpy node in the module's domain."""
    peer = DdsPeer(dds_domain)
    yield peer
    peer.close()


@pytest.fixture(scope="module")
def lk(router: str, dds_domain: int) -> Iterator[LaunchkitPeer]:
    """A launchkit node on the module's router."""
    peer = LaunchkitPeer(router, dds_domain)
    yield peer
    peer.close()
