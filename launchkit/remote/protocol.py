"""What a launcher and an agent say to each other over Zenoh.

Keys (the agent's ``NAME`` and the launch's id are single key chunks; a label is quoted)::

    launchkit/agent/NAME/instance/ID     liveliness: the agent is up (ID changes per start)
    launchkit/agent/NAME/requests        queryable: start a process, signal it
    launchkit/launch/LAUNCH/launcher     liveliness: the launcher is up
    launchkit/launch/LAUNCH/events/LABEL/N   the agent's output lines and exit of LABEL's
                                         N-th incarnation

Every payload is sealed: ``{"body": JSON text, "mac": HMAC-SHA256(key, body)}`` with the agent
key (:mod:`launchkit.remote.keys`); requests also carry a time and a nonce, so a captured one
cannot be played again. Requests::

    {"op": "start", "launch": ID, "label": "talker-2", "incarnation": 1, "grace": 10.0,
     "spec": {...}}         -> {"ok": true, "pid": 4242} | {"ok": false, "error": "..."}
    {"op": "signal", "launch": ID, "label": "talker-2", "incarnation": 1, "signum": 2}
                            -> {"ok": true}

Events: ``{"kind": "line", "stream": "stdout", "text": "..."}``, ``{"kind": "exit", "code": 0}``.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import re
import sys
import time
import uuid
from collections.abc import Mapping
from typing import Any
from urllib.parse import quote

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import UserError

MAX_SKEW = 300.0  # seconds a request's time may differ from the agent's clock
_NAME = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")


class ProtocolError(Exception):
    """A message that is not sealed with the key, or malformed."""


class AgentNameError(UserError):
    """An agent (machine) name that cannot be a key chunk."""


def check_name(name: str, where: str = "agent name") -> str:
    """``name`` if it is a valid agent name (letters, digits, ``_.-``), else a user error."""
    if not _NAME.match(name):
        raise AgentNameError(
            f"{where} {name!r} is not a valid agent name",
            expected="1-64 letters, digits, '_', '.' or '-'",
        )
    return name


def agent_token(name: str, instance: str) -> str:
    """The liveliness key of one run of agent ``name``."""
    return f"launchkit/agent/{name}/instance/{instance}"


def agent_tokens(name: str = "*") -> str:
    """The liveliness keys of agent ``name`` (every agent by default)."""
    return f"launchkit/agent/{name}/instance/*"


def parse_agent_token(key: str) -> tuple[str, str] | None:
    """(name, instance) of an agent token key."""
    parts = key.split("/")
    if len(parts) == 5 and parts[:2] == ["launchkit", "agent"] and parts[3] == "instance":
        return parts[2], parts[4]
    return None


def agent_requests(name: str) -> str:
    """Where agent ``name`` answers requests."""
    return f"launchkit/agent/{name}/requests"


def launcher_token(launch: str) -> str:
    """The liveliness key of a launcher."""
    return f"launchkit/launch/{launch}/launcher"


LAUNCHER_TOKENS = "launchkit/launch/*/launcher"


def launch_of_token(key: str) -> str:
    """The launch id in a launcher token key."""
    return key.split("/")[2]


def events_key(launch: str, label: str, incarnation: int) -> str:
    """Where the agent publishes one incarnation's output and exit."""
    return f"launchkit/launch/{launch}/events/{quote(label, safe='')}/{incarnation}"


def events_of(launch: str) -> str:
    """Every event of a launch."""
    return f"launchkit/launch/{launch}/events/**"


def new_id() -> str:
    """A fresh launch or agent instance id."""
    return uuid.uuid4().hex[:16]


def seal(key: bytes, message: Mapping[str, Any]) -> bytes:
    """``message`` sealed with ``key``."""
    body = json.dumps(message, separators=(",", ":"))
    mac = hmac.new(key, body.encode(), hashlib.sha256).hexdigest()
    return json.dumps({"body": body, "mac": mac}).encode()


def unseal(key: bytes, data: bytes) -> dict[str, Any]:
    """The message in ``data`` if it was sealed with ``key``; :class:`ProtocolError` if not."""
    try:
        outer = json.loads(data)
        body, mac = str(outer["body"]), str(outer["mac"])
        expected = hmac.new(key, body.encode(), hashlib.sha256).hexdigest()
        if not hmac.compare_digest(mac, expected):
            raise ProtocolError("not sealed with this agent key")
        message = json.loads(body)
    except (ValueError, KeyError, TypeError) as error:
        raise ProtocolError(f"malformed message: {error}") from None
    if not isinstance(message, dict):
        raise ProtocolError("malformed message: not an object")
    return message


def request(op: str, **fields: Any) -> dict[str, Any]:
    """A request with its time and nonce."""
    return {"op": op, "time": time.time(), "nonce": new_id(), **fields}


class NonceCheck:
    """Refuses requests too old, too new, or seen before (within :data:`MAX_SKEW`)."""

    def __init__(self) -> None:
        self._seen: dict[str, float] = {}

    def check(self, message: Mapping[str, Any]) -> None:
        """Raise :class:`ProtocolError` unless ``message`` is fresh and new."""
        now = time.time()
        sent, nonce = float(message.get("time", 0)), str(message.get("nonce", ""))
        if abs(now - sent) > MAX_SKEW:
            raise ProtocolError(f"request time is {now - sent:+.0f} s off this host's clock")
        if not nonce or nonce in self._seen:
            raise ProtocolError("request replayed")
        self._seen = {n: t for n, t in self._seen.items() if now - t < 2 * MAX_SKEW}
        self._seen[nonce] = now


def encode_spec(spec: ProcessSpec) -> dict[str, Any]:
    """What the agent needs of ``spec``: its command (``python`` names this interpreter, which
    the agent replaces with its own), what the launch changed in its environment, its
    generated files (parameters), and how to stop it."""
    return {
        "name": spec.name,
        "cmd": spec.cmd,
        "python": sys.executable,
        "env_changes": spec.env_changes,
        "domain": spec.env.get("ROS_DOMAIN_ID"),
        "files": spec.files,
        "cwd": spec.cwd,
        "emulate_tty": spec.emulate_tty,
        "sigterm_timeout": spec.sigterm_timeout,
        "sigkill_timeout": spec.sigkill_timeout,
    }
