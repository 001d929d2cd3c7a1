"""The federation options that ``launchkit router``, ``launchkit run`` and ``launchkit agent``
share: ``--listen``, ``--connect``, ``--tls``, ``--mtls``, ``--access`` (``docs/multi-host.md``)."""

from __future__ import annotations

import argparse
import os
from typing import TYPE_CHECKING

from launchkit.envvars import ROUTER_ACCESS, ROUTER_CONNECT, ROUTER_LISTEN, ROUTER_MTLS, ROUTER_TLS

if TYPE_CHECKING:
    from launchkit.ros.federation import RouterOptions

_VARIABLES = (ROUTER_ACCESS, ROUTER_CONNECT, ROUTER_LISTEN, ROUTER_MTLS, ROUTER_TLS)


def add_federation_options(parser: argparse.ArgumentParser) -> None:
    """Add the options to ``parser`` (each defaults to its ``LAUNCHKIT_ROUTER_*`` variable)."""
    group = parser.add_argument_group("routers on other hosts (docs/multi-host.md)")
    group.add_argument(
        "--listen",
        action="append",
        default=[],
        metavar="EP",
        help=f"also listen at EP for other hosts, e.g. tls/0.0.0.0:7448 (${ROUTER_LISTEN})",
    )
    group.add_argument(
        "--connect",
        action="append",
        default=[],
        metavar="EP",
        help=f"connect to the router of another host at EP (${ROUTER_CONNECT})",
    )
    tls = group.add_mutually_exclusive_group()
    tls.add_argument(
        "--tls",
        metavar="DIR",
        help=f"TLS for tls/ endpoints: DIR holds ca.pem, cert.pem, key.pem (${ROUTER_TLS})",
    )
    tls.add_argument(
        "--mtls",
        metavar="DIR",
        help=f"mutual TLS: the same, and the other side must show a certificate (${ROUTER_MTLS})",
    )
    group.add_argument(
        "--access",
        metavar="FILE",
        help=f"Zenoh access control rules, a JSON5 access_control section (${ROUTER_ACCESS})",
    )


def federation_options(args: argparse.Namespace) -> RouterOptions:
    """The options parsed into ``args``, completed from the environment (checked: a missing
    certificate or a bad endpoint is a :class:`~launchkit.errors.UserError`)."""
    from launchkit.ros.federation import RouterOptions

    return RouterOptions.from_sources(args.listen, args.connect, args.tls, args.mtls, args.access)


def federation_asked(args: argparse.Namespace) -> bool:
    """Whether ``args`` or the environment ask for anything beyond the loopback router (so
    that a launch without it does not load the ROS layer to find out)."""
    given = args.listen or args.connect or args.tls or args.mtls or args.access
    return bool(given) or any(os.environ.get(name) for name in _VARIABLES)
