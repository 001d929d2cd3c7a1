"""The ROS graph, built from rmw_zenoh liveliness tokens (nodes, publishers, servers...)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

import zenoh

from launchkit.ros.keyexpr import LIVELINESS_PREFIX, Token, parse_token

Listener = Callable[[Token, bool], None]  # (token, appeared)


class Graph:
    """A live view of every token in one ROS domain; wait on it with :meth:`wait_for`."""

    def __init__(self, session: zenoh.Session, domain: int) -> None:
        self._tokens: dict[str, Token] = {}
        self._cond = threading.Condition()
        self._listeners: list[Listener] = []
        self._closed = False
        self._subscriber: Any = session.liveliness().declare_subscriber(
            f"{LIVELINESS_PREFIX}/{domain}/**", self._on_sample, history=True
        )

    def _on_sample(self, sample: zenoh.Sample) -> None:
        key = str(sample.key_expr)
        token = parse_token(key)
        if token is None:
            return
        appeared = sample.kind == zenoh.SampleKind.PUT
        with self._cond:
            if appeared:
                self._tokens[key] = token
            else:
                self._tokens.pop(key, None)
            listeners = list(self._listeners)
            self._cond.notify_all()
        for listener in listeners:
            listener(token, appeared)

    def add_listener(self, listener: Listener) -> None:
        """Call ``listener(token, appeared)`` for every token now known and every change."""
        with self._cond:
            self._listeners.append(listener)
            current = list(self._tokens.values())
        for token in current:
            listener(token, True)

    def remove_listener(self, listener: Listener) -> None:
        """Stop calling ``listener``."""
        with self._cond:
            if listener in self._listeners:
                self._listeners.remove(listener)

    def tokens(self, kind: str | None = None, topic: str | None = None) -> list[Token]:
        """Known tokens, optionally only of one kind (NN, MP, MS, SS, SC) and one topic."""
        with self._cond:
            return [
                t
                for t in self._tokens.values()
                if (kind is None or t.kind == kind) and (topic is None or t.topic == topic)
            ]

    def wait_for(self, predicate: Callable[[], bool], timeout: float | None) -> bool:
        """Block until ``predicate()`` holds (re-checked on every graph change) or timeout."""
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._cond:
            while not predicate():
                if self._closed:
                    return False
                remaining = None if deadline is None else deadline - time.monotonic()
                if remaining is not None and remaining <= 0:
                    return False
                self._cond.wait(remaining if remaining is None else min(remaining, 0.5))
            return True

    def close(self) -> None:
        """Stop following the graph (wakes any waiter)."""
        with self._cond:
            self._closed = True
            self._listeners.clear()
            self._cond.notify_all()
        try:
            self._subscriber.undeclare()
        except Exception:  # the session may already be closed
            pass
