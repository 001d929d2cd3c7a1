"""What a launcher and an agent say to each other over Zenoh.

Keys (the agent's ``NAME`` and the launch's id are single key chunks; a label is quoted)::

    launchkit/agent/NAME/instance/ID     liveliness: agent NAME runs (ID changes per start);
                                         a hint only: tokens are not sealed
    launchkit/agent/NAME/requests        queryable: the agent's requests
    launchkit/launch/LAUNCH/events/LABEL/N   the agent's output lines and exit of LABEL's
                                         N-th incarnation

Every payload is sealed (:mod:`launchkit.remote.sealing`). Requests (each with the agent's
``agent`` name and ``instance``, the ``launch`` and the launcher's request number ``seq``)::

    {"op": "hello"}          -> {"ok": true}   the only request without ``instance``: the
                                               sealed answer tells the launcher the instance
    {"op": "start", "label": "talker-2", "incarnation": 1, "grace": 10.0, "spec": {...}}
                             -> {"ok": true, "pid": 4242} | {"ok": false, "error": "..."}
    {"op": "signal", "label": "talker-2", "incarnation": 1, "signum": 2}  -> {"ok": true}
    {"op": "alive", "grace": 10.0}   -> {"ok": true}   the launcher is alive (every
                                               :func:`heartbeat_period` seconds)

Every answer repeats ``launch``, ``seq``, ``agent`` and ``instance``; a request for another
run of the agent gets ``{"ok": false, "restarted": true}``. Events: ``{"kind": "line", "stream":
"stdout", "text": "..."}`` and ``{"kind": "exit", "code": 0}``, with ``label``,
``incarnation`` and their own ``seq``.
"""

from __future__ import annotations

import re
import secrets
import sys
from typing import Any
from urllib.parse import quote

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import UserError

_NAME = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")


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


def events_key(launch: str, label: str, incarnation: int) -> str:
    """Where the agent publishes one incarnation's output and exit."""
    return f"launchkit/launch/{launch}/events/{quote(label, safe='')}/{incarnation}"


def events_of(launch: str) -> str:
    """Every event of a launch."""
    return f"launchkit/launch/{launch}/events/**"


def new_id() -> str:
    """A fresh launch or agent instance id (96 random bits: never guessed, never repeated)."""
    return secrets.token_hex(12)


def heartbeat_period(grace: float) -> float:
    """How often a launcher tells an agent it is alive, for a grace period of ``grace``."""
    return min(1.0, max(0.1, grace / 4))


def silence_limit(grace: float) -> float:
    """How long an agent waits without a word of a launcher before it stops that launch's
    processes (the grace period, but never less than three heartbeats)."""
    return max(grace, 3 * heartbeat_period(grace))


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
