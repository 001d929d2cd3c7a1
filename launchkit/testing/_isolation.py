"""Keeping launches apart: each gets its own router port and ROS domain."""

from __future__ import annotations

import itertools
import os
import socket

ROS_DOMAIN_ENV = "ROS_DOMAIN_ID"
# ROS 2 domain ids that are safe on every platform are 0-101; 0 is everyone's default
_DOMAINS = 101
_WORKER_SPREAD = 50
_counter = itertools.count()


def free_loopback_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def router_endpoint(port: int) -> str:
    """The Zenoh endpoint of a loopback router on ``port``."""
    return f"tcp/127.0.0.1:{port}"


def domain_id() -> int:
    """A ROS domain in 1..101 for the next launch: consecutive launches of one process get
    different domains, and xdist workers (``gw0``, ``gw1``, ...) start far apart.

    The router port is what really separates launches; the domain is a second fence.
    """
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw")
    offset = int(worker) * _WORKER_SPREAD if worker.isdigit() else 0
    return 1 + (offset + next(_counter)) % _DOMAINS
