"""Keeping launches apart: each gets its own router port, ROS domain and viewer port, and
none of the shell's launchkit settings."""

from __future__ import annotations

import functools
import itertools
import os
import random
import socket
from collections.abc import Mapping
from pathlib import Path

from launchkit.envvars import CACHE_DIR, NAMES

ROS_DOMAIN_ENV = "ROS_DOMAIN_ID"
# ROS 2 domain ids that are safe on every platform are 0-101; 0 is everyone's default
_DOMAINS = 101
_WORKER_SPREAD = 50
_counter = itertools.count()
# DDS (RTPS) gives domain d the UDP ports 7400 + 250·d and the 249 after them
_RTPS_BASE, _RTPS_GAIN = 7400, 250
# free ports are picked from here up to the ephemeral range, when it leaves this much room
_PICK_FROM, _PICK_ROOM = 20000, 2000
# seeded by the system, never by a test (hypothesis seeds the random module: two workers would
# pick the same ports)
_PICKER = random.SystemRandom()
# the LAUNCHKIT_* variables a launch never inherits from the test process
_SHELL_SETTINGS = frozenset(NAMES) - {CACHE_DIR}


def free_loopback_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on right now.

    Picked below the kernel's range of ephemeral ports where there is room: outgoing
    connections take their local ports from that range, so a port picked there (as binding port
    0 picks) could be taken by some connection before the server meant to get it binds.
    """
    low = first_ephemeral_port()
    if low - _PICK_FROM >= _PICK_ROOM:
        for _ in range(50):
            port = _PICKER.randrange(_PICK_FROM, low)
            if _bindable(port):
                return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _bindable(port: int) -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        try:
            probe.bind(("127.0.0.1", port))
        except OSError:
            return False
        return True


@functools.cache
def first_ephemeral_port() -> int:
    """The lowest of the kernel's ephemeral ports (Linux's default where it cannot be read)."""
    try:
        return int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768


def without_shell_settings(environ: Mapping[str, str]) -> dict[str, str]:
    """``environ`` without its ``LAUNCHKIT_*`` settings (``launchkit.envvars``), but for the
    cache folder (it changes nothing but speed): a launch a test starts must not join the router,
    the federation or the viewer port a user's shell names, nor log by that shell's limits."""
    return {name: value for name, value in environ.items() if name not in _SHELL_SETTINGS}


def router_endpoint(port: int) -> str:
    """The Zenoh endpoint of a loopback router on ``port``."""
    return f"tcp/127.0.0.1:{port}"


def domain_id() -> int:
    """A ROS domain in 1..101 for the next launch: consecutive launches of one process get
    different domains, and xdist workers (``gw0``, ``gw1``, ...) and test runs start apart.

    The router port is what really separates launches; the domain is a second fence, for real
    DDS nodes (the bridge's tests). The domain the shell's ``ROS_DOMAIN_ID`` names (where the
    user's own nodes may be running) is never chosen, and a domain some DDS participant on this
    machine already uses (another test run's, say) is passed over while a free one is left.
    """
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw")
    # the process id spreads two test runs started at the same moment (their DDS ports are
    # not bound yet when both choose)
    offset = int(worker) * _WORKER_SPREAD if worker.isdigit() else 0
    offset += os.getpid() % _WORKER_SPREAD
    users = os.environ.get(ROS_DOMAIN_ENV, "0").strip()
    busy = _udp_ports_in_use()
    tried: list[int] = []
    for _ in range(_DOMAINS):
        domain = 1 + (offset + next(_counter)) % _DOMAINS
        if str(domain) == users:
            continue
        if not _domain_busy(domain, busy):
            return domain
        tried.append(domain)
    return tried[0]  # every domain busy: the first one tried


def _domain_busy(domain: int, ports: set[int]) -> bool:
    first = _RTPS_BASE + _RTPS_GAIN * domain
    return any(first <= port < first + _RTPS_GAIN for port in ports)


def _udp_ports_in_use() -> set[int]:
    """The local UDP ports bound on this machine (from /proc; empty where there is none)."""
    ports = set()
    for table in ("/proc/net/udp", "/proc/net/udp6"):
        try:
            rows = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for row in rows:
            fields = row.split()
            if len(fields) > 1:
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports
