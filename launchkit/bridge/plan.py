"""Deciding what to bridge: a pure function of the two sides' graphs and the user's filters.

A topic is bridged from a side where it has publishers to the other side; the bridge's
subscription on the source side exists only while the other side has subscriptions (or always,
for transient-local topics, so that latecomers get the cached samples), so an unwatched camera
costs nothing. A service is bridged from the side that has a server to the side that has none.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

from launchkit.bridge.graph_view import GraphView
from launchkit.errors import UserError
from launchkit.ros.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

ZENOH, DDS = "launchkit", "DDS"


class FilterError(UserError):
    """A ``--topics`` / ``--exclude`` value that is not a regular expression."""


@dataclass(frozen=True)
class NameFilter:
    """Which names to bridge: any ``--topics`` pattern matches and no ``--exclude`` does."""

    include: tuple[re.Pattern[str], ...] = ()
    exclude: tuple[re.Pattern[str], ...] = ()

    @classmethod
    def parse(cls, include: Sequence[str], exclude: Sequence[str]) -> NameFilter:
        """Compile the patterns (matched against the whole name); a bad one is a user error."""
        return cls(_compile("--topics", include), _compile("--exclude", exclude))

    def accepts(self, name: str) -> bool:
        """Whether ``name`` is bridged."""
        if self.include and not any(p.fullmatch(name) for p in self.include):
            return False
        return not any(p.fullmatch(name) for p in self.exclude)


def _compile(option: str, patterns: Sequence[str]) -> tuple[re.Pattern[str], ...]:
    compiled = []
    for pattern in patterns:
        try:
            compiled.append(re.compile(pattern))
        except re.error as exc:
            raise FilterError(
                f"{option} {pattern!r}: {exc}", expected="a Python regular expression"
            ) from None
    return tuple(compiled)


@dataclass(frozen=True)
class TopicRoute:
    """Bridge ``topic`` of ``type_name`` from ``source`` to the other side with ``qos``."""

    topic: str
    type_name: str
    source: str
    qos: QoSProfile
    active: bool  # subscribe on the source side now

    @property
    def key(self) -> tuple[str, str]:
        """What identifies the route (a change of type, QoS or activity rebuilds it)."""
        return (self.source, self.topic)


@dataclass(frozen=True)
class ServiceRoute:
    """Serve ``service`` of ``type_name`` on the side opposite ``source`` (where the server is)."""

    service: str
    type_name: str
    source: str

    @property
    def key(self) -> tuple[str, str]:
        """What identifies the route."""
        return (self.source, self.service)


def mirrored_qos(publishers: Sequence[QoSProfile]) -> QoSProfile:
    """One profile that every publisher can feed and that offers what they offer.

    Reliable only if all are (a DDS reliable reader matches no best-effort writer), transient
    local only if all are, the deepest depth (rmw_zenoh's 42 for an unknown depth).
    """
    reliable = all(p.reliability == ReliabilityPolicy.RELIABLE for p in publishers)
    latched = all(p.durability == DurabilityPolicy.TRANSIENT_LOCAL for p in publishers)
    return QoSProfile(
        depth=max((p.effective_depth for p in publishers), default=10),
        reliability=ReliabilityPolicy.RELIABLE if reliable else ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
        history=HistoryPolicy.KEEP_LAST,
    )


@dataclass
class Plan:
    """The routes wanted now, and why some names are not bridged (for one warning each)."""

    topics: dict[tuple[str, str], TopicRoute]
    services: dict[tuple[str, str], ServiceRoute]
    skipped: dict[str, str]  # name -> reason


def plan(
    zenoh: GraphView,
    dds: GraphView,
    names: NameFilter,
    bridge_services: bool = True,
) -> Plan:
    """The routes between ``zenoh`` (launchkit) and ``dds`` for names that ``names`` accepts."""
    result = Plan({}, {}, {})
    for source, here, there in ((ZENOH, zenoh, dds), (DDS, dds, zenoh)):
        for topic, ends in here.topics.items():
            if not ends.publishers or not names.accepts(topic):
                continue
            types = ends.types | there.topics.get(topic, ends).types
            if len(types) != 1:
                result.skipped[topic] = f"more than one type ({', '.join(sorted(types))})"
                continue
            qos = mirrored_qos(ends.publishers)
            listeners = there.topics.get(topic)
            active = qos.durability == DurabilityPolicy.TRANSIENT_LOCAL or bool(
                listeners and listeners.subscriptions
            )
            route = TopicRoute(topic, next(iter(types)), source, qos, active)
            result.topics[route.key] = route
        if not bridge_services:
            continue
        for service, servers in here.services.items():
            if not servers.servers or not names.accepts(service):
                continue
            if service in there.services:  # a real server on both sides: each uses its own
                continue
            if len(servers.types) != 1:
                listed = ", ".join(sorted(servers.types))
                result.skipped[service] = f"more than one type ({listed})"
                continue
            service_route = ServiceRoute(service, next(iter(servers.types)), source)
            result.services[service_route.key] = service_route
    return result
