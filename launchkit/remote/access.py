"""Which hosts may reach an agent at all: Zenoh access control made from ``--launchers``.

``launchkit agent --mtls DIR --launchers robot,laptop`` hosts its router with Zenoh's own
access control (the ``access_control`` section, :class:`~launchkit.ros.federation.RouterOptions`
``rules``): everything is denied but to this host's own processes (the loopback interface)
and to the hosts whose certificate's common name is listed. Mutual TLS proves the names: a
certificate signed by the user's CA is the only way to one. Every other host, even one with a
certificate from the same CA, has no traffic through this router (it can neither ask the agent
nor see this host's topics). The agent key is still needed on top (the local users of this
host reach the router through loopback): see docs/multi-host.md, "Threat model".
"""

from __future__ import annotations

import json
import re
import socket
from collections.abc import Sequence
from pathlib import Path

from launchkit.errors import UserError

#: Every kind of message Zenoh's access control knows (zenoh 1.x).
MESSAGES = (
    "put",
    "delete",
    "declare_subscriber",
    "query",
    "declare_queryable",
    "reply",
    "liveliness_token",
    "declare_liveliness_subscriber",
    "liveliness_query",
)
_IFF_LOOPBACK = 0x8
_NAME = re.compile(r"^[^\s,]{1,253}$")


class LaunchersError(UserError):
    """``--launchers`` given where it cannot protect the agent."""


def parse_launchers(text: str) -> tuple[str, ...]:
    """The certificate names in ``--launchers`` (comma or space separated)."""
    names = tuple(dict.fromkeys(text.replace(",", " ").split()))
    bad = [name for name in names if not _NAME.match(name)]
    if not names or bad:
        raise LaunchersError(
            f"--launchers {text!r} is not a list of certificate names",
            expected="common names (CN) of the launching hosts' certificates, e.g. robot,laptop",
        )
    return names


def loopback_interfaces() -> list[str]:
    """This host's loopback network interfaces (``lo`` on Linux)."""
    found = []
    for _index, name in socket.if_nameindex():
        try:
            flags = int((Path("/sys/class/net") / name / "flags").read_text(), 16)
        except (OSError, ValueError):
            flags = _IFF_LOOPBACK if name == "lo" else 0
        if flags & _IFF_LOOPBACK:
            found.append(name)
    return found or ["lo"]


def launcher_rules(launchers: Sequence[str]) -> str:
    """The ``access_control`` section admitting this host's processes and ``launchers``."""
    everything = {
        "id": "everything",
        "messages": list(MESSAGES),
        "flows": ["ingress", "egress"],
        "permission": "allow",
        "key_exprs": ["**"],
    }
    section = {
        "enabled": True,
        "default_permission": "deny",
        "rules": [everything],
        "subjects": [
            {"id": "this_host", "interfaces": loopback_interfaces()},
            {"id": "launchers", "cert_common_names": list(launchers)},
        ],
        "policies": [{"rules": ["everything"], "subjects": ["this_host", "launchers"]}],
    }
    return json.dumps(section)
