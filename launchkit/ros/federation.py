"""Routers across machines: where a router also listens and which routers it connects to,
with TLS, mutual TLS and Zenoh's access control (``docs/multi-host.md``).

Zenoh routers that connect to each other route every key between their peers, so nodes on two
hosts see one graph. launchkit's own endpoint (``--router``) stays on loopback for the local
nodes; :class:`RouterOptions` adds the endpoints other hosts use. Each option has a variable
(``LAUNCHKIT_ROUTER_LISTEN`` ...), read by every router launchkit hosts, so a shell that sets
``LAUNCHKIT_ROUTER_CONNECT`` makes even the shared background router join another host's graph.

Kept free of Zenoh: :meth:`RouterOptions.settings` gives the configuration keys to insert.
"""

from __future__ import annotations

import ipaddress
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from launchkit.envvars import (
    ROUTER_ACCESS,
    ROUTER_CONNECT,
    ROUTER_LISTEN,
    ROUTER_MTLS,
    ROUTER_TLS,
)
from launchkit.errors import UserError
from launchkit.ros.endpoints import host_port, validate_endpoint

#: What a TLS folder holds: the CA that signed every host's certificate, and this host's.
TLS_FILES = {"root_ca_certificate": "ca.pem", "certificate": "cert.pem", "private_key": "key.pem"}
_ENCRYPTED = ("tls", "quic")


class RouterOptionsError(UserError):
    """A federation option that cannot be used (a missing certificate, a bad endpoint)."""


@dataclass(frozen=True)
class RouterOptions:
    """Extra ``listen`` and ``connect`` endpoints, a ``tls`` folder (``mtls``: clients must
    show a certificate too) and an ``access`` control file, or access control ``rules`` made by
    launchkit (JSON text, for ``launchkit agent --launchers``); empty: loopback only."""

    listen: tuple[str, ...] = ()
    connect: tuple[str, ...] = ()
    tls: str | None = None
    mtls: bool = False
    access: str | None = None
    rules: str | None = None

    @classmethod
    def from_sources(
        cls,
        listen: Iterable[str] = (),
        connect: Iterable[str] = (),
        tls: str | None = None,
        mtls: str | None = None,
        access: str | None = None,
        environ: Mapping[str, str] | None = None,
    ) -> RouterOptions:
        """Options from the command line, each falling back on its variable when not given;
        endpoints and files are checked (:class:`RouterOptionsError`)."""
        env = os.environ if environ is None else environ
        listen = list(listen) or _split(env.get(ROUTER_LISTEN, ""))
        connect = list(connect) or _split(env.get(ROUTER_CONNECT, ""))
        if tls and mtls:
            raise RouterOptionsError("--tls and --mtls both given", expected="one of them")
        if not (tls or mtls):
            tls, mtls = env.get(ROUTER_TLS) or None, env.get(ROUTER_MTLS) or None
        folder = mtls or tls
        options = cls(
            tuple(validate_endpoint(e) for e in listen),
            tuple(validate_endpoint(e) for e in connect),
            _tls_folder(folder) if folder else None,
            bool(mtls),
            _access_file(access or env.get(ROUTER_ACCESS) or None),
        )
        encrypted = [e for e in (*options.listen, *options.connect) if _protocol(e) in _ENCRYPTED]
        if encrypted and options.tls is None:
            raise RouterOptionsError(
                f"{encrypted[0]} needs certificates",
                expected=f"--tls DIR or --mtls DIR (or ${ROUTER_TLS} / ${ROUTER_MTLS})",
            )
        return options

    @property
    def empty(self) -> bool:
        """Whether nothing beyond the loopback router is asked for."""
        return self == RouterOptions()

    def settings(self, endpoint: str) -> dict[str, Any]:
        """Zenoh configuration keys for a router whose own endpoint is ``endpoint``."""
        settings: dict[str, Any] = {
            "listen/endpoints": list(dict.fromkeys((endpoint, *self.listen))),
            "connect/endpoints": list(self.connect),
        }
        if self.tls is not None:
            files = {key: str(Path(self.tls) / name) for key, name in TLS_FILES.items()}
            settings["transport/link/tls"] = {
                "root_ca_certificate": files["root_ca_certificate"],
                "listen_certificate": files["certificate"],
                "listen_private_key": files["private_key"],
                "connect_certificate": files["certificate"],
                "connect_private_key": files["private_key"],
                "enable_mtls": self.mtls,
            }
        return settings

    def access_control(self) -> str | None:
        """The JSON5 text of the ``access_control`` section, if an access file or rules are
        given."""
        if self.rules is not None:
            return self.rules
        return None if self.access is None else Path(self.access).read_text()

    def exposure_warnings(self, endpoint: str) -> list[str]:
        """What is exposed beyond this machine, one warning per risky listen endpoint."""
        warnings = []
        for listen in dict.fromkeys((endpoint, *self.listen)):
            if _on_loopback(listen):
                continue
            if _protocol(listen) not in _ENCRYPTED:
                warnings.append(
                    f"listening on {listen} without TLS: anyone who can reach this address "
                    "can read every topic, publish to the robot (cmd_vel) and call its "
                    "services, and the traffic is readable on the network; use a tls/ "
                    "endpoint with --mtls (docs/multi-host.md)"
                )
            elif not self.mtls and self.access is None and self.rules is None:
                warnings.append(
                    f"listening on {listen} with server-only TLS: the traffic is encrypted "
                    "but any client can connect and command the robot; use --mtls to admit "
                    "only holders of a certificate from your CA (docs/multi-host.md)"
                )
        return warnings


def _split(text: str) -> list[str]:
    return [item for item in text.replace(",", " ").split() if item]


def _protocol(endpoint: str) -> str:
    return endpoint.partition("/")[0]


def _on_loopback(endpoint: str) -> bool:
    host, _ = host_port(endpoint)
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False  # a name: assume it is reachable from elsewhere


def _tls_folder(folder: str) -> str:
    path = Path(folder).expanduser().resolve()
    missing = [name for name in TLS_FILES.values() if not (path / name).is_file()]
    if missing:
        raise RouterOptionsError(
            f"TLS folder {folder}: missing {', '.join(missing)}",
            expected="a folder with ca.pem (your CA), cert.pem and key.pem (this host's)",
        )
    return str(path)


def _access_file(access: str | None) -> str | None:
    if access is None:
        return None
    path = Path(access).expanduser().resolve()
    if not path.is_file():
        raise RouterOptionsError(
            f"access control file {access} does not exist",
            expected="a JSON5 file with Zenoh's access_control section",
        )
    return str(path)


def describe(options: RouterOptions) -> Sequence[str]:
    """One line per federation setting, for a router's start-up message."""
    lines = [f"also listening at {e}" for e in options.listen]
    lines += [f"connecting to {e}" for e in options.connect]
    if options.tls:
        kind = "mutual TLS" if options.mtls else "TLS"
        lines.append(f"{kind} with the certificates in {options.tls}")
    if options.access:
        lines.append(f"access control from {options.access}")
    return lines
