"""The link watch reports a link that was replaced between two of its looks (the other router
restarted quickly) as lost and linked again, not as nothing."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Any

from launchkit.ros import router_links
from launchkit.ros.router_links import LinkWatch

ENDPOINT = "tcp/127.0.0.1:7448"


@dataclass
class _Link:
    dst: str
    src: str
    zid: str


@dataclass
class _Info:
    current: list[_Link] = field(default_factory=list)
    looked: threading.Event = field(default_factory=threading.Event)

    def links(self) -> list[_Link]:
        self.looked.set()
        return list(self.current)


@dataclass
class _Session:
    info: _Info = field(default_factory=_Info)


def _next_look(info: _Info) -> None:
    info.looked.clear()
    assert info.looked.wait(5)
    info.looked.clear()
    assert info.looked.wait(5)  # a whole look after the change


def test_a_link_replaced_between_looks_is_reported_lost_and_linked(monkeypatch: Any) -> None:
    monkeypatch.setattr(router_links, "PERIOD", 0.01)
    said: list[str] = []
    session = _Session()
    watch = LinkWatch(session, [ENDPOINT], lambda level, text: said.append(f"{level}: {text}"))
    try:
        session.info.current = [_Link(ENDPOINT, "tcp/127.0.0.1:50000", "aa")]
        _next_look(session.info)
        assert said == [f"info: linked to the router at {ENDPOINT}"]
        # the other router restarted: a new id and a new socket, with no gap seen
        session.info.current = [_Link(ENDPOINT, "tcp/127.0.0.1:50001", "bb")]
        _next_look(session.info)
        assert said[1:] == [
            f"warn: lost the link to the router at {ENDPOINT}; retrying",
            f"info: linked to the router at {ENDPOINT}",
        ]
        _next_look(session.info)
        assert len(said) == 3  # an unchanged link says nothing more
        assert watch.linked() == {ENDPOINT}
    finally:
        watch.close()
