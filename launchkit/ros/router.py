"""A Zenoh router hosted by this process (a launch's, ``launchkit router``'s, or the shared
background one's), or joined when one of this user's already listens at the endpoint."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import zenoh

from launchkit.errors import RuntimeLaunchError
from launchkit.ros.endpoints import host_port, router_endpoint
from launchkit.ros.federation import RouterOptions
from launchkit.ros.router_access import router_answers
from launchkit.ros.router_links import LinkWatch, Report
from launchkit.ros.rundir import RunDirError, locked, router_file
from launchkit.ros.session import close_session, open_session, router_config

LOCK_TIMEOUT = 60.0  # seconds to wait for another process that is starting a router here


@dataclass
class RouterHandle:
    """A running router: ``endpoint``, whether this process ``hosted`` it (else it joined
    one, ``shared`` when that is the shared background router), and ``close()``."""

    endpoint: str
    hosted: bool
    _session: Any = field(default=None, repr=False)
    shared: bool = False
    #: what it exposes beyond this machine (one warning each), for the caller to show
    warnings: list[str] = field(default_factory=list)
    _links: LinkWatch | None = field(default=None, repr=False)

    def sessions(self) -> int:
        """How many nodes, commands and other peers are connected to the router this process
        hosts (other routers not counted); 0 for a joined router."""
        if self._session is None:
            return 0
        return sum(1 for t in self._session.info.transports() if t.whatami != zenoh.WhatAmI.ROUTER)

    def linked(self) -> set[str]:
        """The ``connect`` endpoints with a link up now."""
        return set() if self._links is None else self._links.linked()

    def close(self) -> None:
        """Stop the router if this process hosts it (joined routers are left alone)."""
        if self._links is not None:
            self._links.close()
            self._links = None
        if self._session is not None:
            close_session(self._session)
            self._session = None


def start_router(
    endpoint: str | None = None,
    *,
    lock: bool = True,
    options: RouterOptions | None = None,
    report: Report | None = None,
) -> RouterHandle:
    """Start a router at ``endpoint`` (default ``$LAUNCHKIT_ROUTER`` or tcp/127.0.0.1:7447).

    If one of this user's routers already listens there, join it instead (``hosted`` is
    False); another user's is refused (:class:`~launchkit.ros.router_access.ForeignRouterError`).
    ``lock``: take the endpoint's lock file while starting, so that a shared router being
    started by another process at the same moment is joined, not raced (the shared router's
    own start holds that lock already and passes False). ``options``: the endpoints, TLS and
    access control that reach other hosts (default: from the ``LAUNCHKIT_ROUTER_*``
    variables); ``report(level, message)`` is told when links to other routers come and go.
    """
    endpoint = router_endpoint(endpoint)
    options = RouterOptions.from_sources() if options is None else options
    try:
        lock_file = router_file(*host_port(endpoint), "lock") if lock else None
    except RunDirError:
        lock_file = None  # no private folder for the lock: binding first still decides
    if lock_file is None:
        return _host_or_join(endpoint, options, report)
    with locked(lock_file, LOCK_TIMEOUT, f"starting a router at {endpoint}"):
        return _host_or_join(endpoint, options, report)


def _host_or_join(endpoint: str, options: RouterOptions, report: Report | None) -> RouterHandle:
    if router_answers(endpoint):
        return _joined(endpoint)
    config = router_config(endpoint, options)
    try:
        session = open_session(config)
    except Exception as exc:  # zenoh raises a bare ZError
        if router_answers(endpoint):  # lost a race with a process that took no lock
            return _joined(endpoint)
        raise RuntimeLaunchError(f"cannot start the ROS router at {endpoint}: {exc}") from None
    handle = RouterHandle(endpoint, hosted=True, _session=session)
    handle.warnings = options.exposure_warnings(endpoint)
    if options.connect:
        handle._links = LinkWatch(session, options.connect, report or _quiet)
    return handle


def _quiet(level: str, message: str) -> None:
    pass


def _joined(endpoint: str) -> RouterHandle:
    from launchkit.ros.shared_router import SharedRouterState

    return RouterHandle(endpoint, hosted=False, shared=SharedRouterState.read(endpoint) is not None)


__all__ = ["RouterHandle", "RouterOptions", "start_router"]
