"""What every ``launchkit topic|node|service|param|interface`` command shares."""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Iterator
from contextlib import contextmanager

from launchkit.envvars import ROUTER
from launchkit.errors import UserError
from launchkit.ros.context import Context
from launchkit.ros.endpoints import router_endpoint
from launchkit.ros.graph import snapshot
from launchkit.ros.keyexpr import Token
from launchkit.ros.logging import get_logger
from launchkit.ros.node import Node
from launchkit.ros.shared_router import ensure_router


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
    """Point this process at the router the user chose, once one answers there: the shared
    background router is started when none does on loopback, else the command waits for one,
    saying so once (as rmw_zenoh's nodes do); another user's router is refused."""
    endpoint = router_endpoint(getattr(args, "router", None))
    os.environ[ROUTER] = endpoint
    ensure_router(endpoint, wait=True, say=_say)
    return endpoint


def _say(level: str, message: str) -> None:
    getattr(get_logger("launchkit"), level)(message)


@contextmanager
def cli_node(args: argparse.Namespace) -> Iterator[Node]:
    """A hidden node for one command, its context shut down afterwards."""
    use_router(args)
    context = Context(start_router=False)  # use_router decided already
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
