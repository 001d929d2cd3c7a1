"""Sealed messages between launchers and agents, and the agent's guard against replays.

Zenoh's mutual TLS and access control decide which hosts may reach an agent's keys at all
(docs/multi-host.md, "Threat model"); every local user of either machine can still reach the
loopback routers, so each message is also sealed with the agent key: an HMAC-SHA256 of its
JSON body. The body binds everything a receiver acts on, so a sealed message means one thing
only:

* ``dir``: ``request`` (launcher to agent), ``reply`` (agent to launcher) or ``event`` (the
  agent's output lines and exits): a message cannot be passed off in another direction;
* ``agent`` and ``instance``: the agent's name and the id of its current run, fresh at every
  start, so nothing sealed for one run of an agent means anything to the next;
* ``launch``: the launch's id, fresh at every start of a launcher;
* ``seq``: the launcher's request counter (requests, and replies, which repeat their
  request's ``launch`` and ``seq``: each reply is tied to its request), or the event counter of
  one incarnation of one process (events, which also name their ``label`` and
  ``incarnation``).

An agent executes each (``launch``, ``seq``) once per run (:class:`ReplayGuard`); a copy
gets the first answer again, never a second effect. A request for another run of the agent is
refused, whatever its age. Unsealed or malformed requests get an unsealed answer: nothing the
agent signs is ever handed to a sender without the key.
"""

from __future__ import annotations

import hashlib
import hmac
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

VERSION = 1
#: How far below the highest request number seen a late request may still arrive (requests
#: of one launch travel on several threads and may overtake each other).
WINDOW = 1024
#: Seconds without a request after which a launch counts as ended on an agent.
FORGET_AFTER = 600.0

REQUEST, REPLY, EVENT = "request", "reply", "event"


class ProtocolError(Exception):
    """A message that is not sealed with the key, malformed, or not meant for its receiver."""


def seal(key: bytes, direction: str, message: Mapping[str, Any]) -> bytes:
    """``message`` marked with its ``direction`` and sealed with ``key``."""
    body = json.dumps({**message, "v": VERSION, "dir": direction}, separators=(",", ":"))
    mac = hmac.new(key, body.encode(), hashlib.sha256).hexdigest()
    return json.dumps({"body": body, "mac": mac}).encode()


def unseal(key: bytes, direction: str, data: bytes) -> dict[str, Any]:
    """The message in ``data`` if ``key`` sealed it for ``direction``; else
    :class:`ProtocolError`."""
    try:
        outer = json.loads(data)
        body, mac = str(outer["body"]), str(outer["mac"])
    except (ValueError, KeyError, TypeError) as error:
        raise ProtocolError(f"malformed message: {error}") from None
    expected = hmac.new(key, body.encode(), hashlib.sha256).hexdigest()
    if not hmac.compare_digest(mac, expected):
        raise ProtocolError("not sealed with this agent key")
    message = json.loads(body)
    if not isinstance(message, dict) or message.get("v") != VERSION:
        raise ProtocolError("not a message of this protocol version")
    if message.get("dir") != direction:
        raise ProtocolError(f"a sealed {message.get('dir')!r} where a {direction!r} belongs")
    return message


def unsealed_refusal(error: str) -> bytes:
    """What an agent answers a sender without the key: plain text, signed by nobody."""
    return json.dumps({"refused": error}).encode()


def refusal_of(data: bytes) -> str | None:
    """The text of an unsealed refusal, if ``data`` is one."""
    try:
        value = json.loads(data)
    except ValueError:
        return None
    return str(value["refused"]) if isinstance(value, dict) and "refused" in value else None


@dataclass
class _Launch:
    """What one run of an agent remembers of one launch's requests."""

    highest: int = 0
    answers: dict[int, dict[str, Any]] = field(default_factory=dict)
    last: float = 0.0
    ended: bool = False


class ReplayGuard:
    """The requests one run of an agent has executed, per launch, with their answers.

    A request is new when its number is above the highest seen minus :data:`WINDOW` and was not
    seen; a copy of a recent one gets the answer of the first; anything older is refused. A
    launch silent for :data:`FORGET_AFTER` seconds (its launcher, alive, asks every second) is
    ended here: its answers are dropped and its requests refused from then on.
    """

    def __init__(self) -> None:
        self._launches: dict[str, _Launch] = {}

    def answer_of(self, launch: str, seq: int, now: float) -> dict[str, Any] | None:
        """The answer already given to (``launch``, ``seq``); None when it is new;
        :class:`ProtocolError` when it cannot be told from a replay."""
        self._forget(now)
        if seq < 1:
            raise ProtocolError("a request without its number")
        record = self._launches.get(launch)
        if record is None:
            return None
        if record.ended:
            raise ProtocolError(f"launch {launch} ended here: replayed")
        if seq in record.answers:
            return record.answers[seq]
        if seq <= record.highest - WINDOW:
            raise ProtocolError(f"request {seq} of launch {launch} is too old: replayed")
        return None

    def remember(self, launch: str, seq: int, answer: dict[str, Any], now: float) -> None:
        """Record the answer given to a new request."""
        record = self._launches.setdefault(launch, _Launch())
        record.highest = max(seq, record.highest)
        record.last = now
        record.answers[seq] = answer
        for old in [n for n in record.answers if n <= record.highest - WINDOW]:
            del record.answers[old]

    def _forget(self, now: float) -> None:
        for record in self._launches.values():
            if not record.ended and now - record.last > FORGET_AFTER:
                record.ended = True
                record.answers = {}
