"""What every ``launchkit topic|node|service|param|interface`` command shares."""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Iterator
from contextlib import contextmanager

from launchkit.envvars import ROUTER
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.ros.context import Context
from launchkit.ros.graph import snapshot
from launchkit.ros.keyexpr import Token
from launchkit.ros.node import Node
from launchkit.ros.router import is_listening
from launchkit.ros.session import router_endpoint


class CliUsageError(UserError):
    """A command-line mistake found after parsing (unknown node, topic, ...)."""


def add_router_option(parser: argparse.ArgumentParser) -> None:
    """``--router tcp/HOST:PORT`` (default ``$LAUNCHKIT_ROUTER`` or tcp/127.0.0.1:7447)."""
    parser.add_argument(
        "--router",
        metavar="tcp/HOST:PORT",
        help=f"the Zenoh router to connect to (default ${ROUTER} or tcp/127.0.0.1:7447)",
    )
    parser.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)


def use_router(args: argparse.Namespace) -> str:
    """Point this process at the router the user chose; fail clearly if none answers."""
    endpoint = router_endpoint(getattr(args, "router", None))
    os.environ[ROUTER] = endpoint
    if not is_listening(endpoint, timeout=1.0):
        raise RuntimeLaunchError(
            f"no ROS router answers at {endpoint} (start `launchkit run ...` or "
            f"`launchkit router`, or set {ROUTER} / --router)"
        )
    return endpoint


@contextmanager
def cli_node(args: argparse.Namespace) -> Iterator[Node]:
    """A hidden node for one command, its context shut down afterwards."""
    use_router(args)
    context = Context()
    context.init([])
    try:
        yield Node(f"_launchkit_cli_{os.getpid()}", context=context, start_parameter_services=False)
    finally:
        context.shutdown()


_SETTLE = 0.5  # seconds a fresh session may need before the router routes liveliness queries


def graph_tokens(node: Node, timeout: float = 2.0) -> list[Token]:
    """Every token in the node's domain, without the command's own.

    Just after a session connects, the router may not route liveliness queries yet (measured:
    up to ~60 ms) and answers nothing or part of the graph; so ask until two answers in a row
    agree (and are not empty), for at most ``_SETTLE`` seconds.
    """
    own = node.zid
    deadline = time.monotonic() + _SETTLE
    previous: set[str] | None = None
    while True:
        tokens = [
            t
            for t in snapshot(node.context.session, node.context.domain_id, timeout)
            if t.zid != own
        ]
        keys = {t.key for t in tokens}
        if (keys and keys == previous) or time.monotonic() > deadline:
            return tokens
        previous = keys
        time.sleep(0.02)


def normalize_topic(name: str) -> str:
    """A topic or service name as the graph holds it (absolute)."""
    return name if name.startswith("/") else "/" + name


def visible(token: Token, include_hidden: bool) -> bool:
    """Hidden nodes (names starting with ``_``) are left out unless asked for."""
    return include_hidden or not token.node_name.startswith("_")


def hidden_name(name: str) -> bool:
    """Whether a topic or service name is hidden (a token of it starts with ``_``), as ros2 topic
    and service list judge it: by the name, not by the node that offers it."""
    return any(token.startswith("_") for token in name.split("/"))
