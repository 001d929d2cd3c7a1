"""What every ``launchkit topic|node|service|param|interface`` command shares."""

from __future__ import annotations

import argparse
import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from launchkit.envvars import ROUTER
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.ros.endpoints import router_endpoint
from launchkit.ros.keyexpr import Token, domain_id
from launchkit.ros.logging import get_logger
from launchkit.ros.shared_router import ensure_router

if TYPE_CHECKING:
    from launchkit.ros.node import Node

# The listing commands (topic list, node info, ...) import only zenoh and the token parser: the
# node API, the message types and numpy are imported by the commands that make a node.


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
    from launchkit.ros.context import Context
    from launchkit.ros.node import Node

    use_router(args)
    context = Context(start_router=False, client=True)  # use_router decided already
    context.init([])
    try:
        with _connecting(context.router):
            node = Node(
                f"_launchkit_cli_{os.getpid()}",
                context=context,
                start_parameter_services=False,
                enable_rosout=False,
            )
        yield node
    finally:
        context.try_shutdown()


def graph_tokens(node: Node, timeout: float = 2.0) -> list[Token]:
    """Every token in the node's domain, without the command's own: one query, answered by
    the router from what it knows (the node's session is its client, see
    :func:`launchkit.ros.session.client_config`)."""
    from launchkit.ros.graph import snapshot

    own = node.zid
    return [
        t for t in snapshot(node.context.session, node.context.domain_id, timeout) if t.zid != own
    ]


def graph_once(args: argparse.Namespace, timeout: float = 2.0) -> list[Token]:
    """Every token of the graph, asked once of the router by a short-lived client session
    (no node: what the listing commands need). Like ``ros2 ... list`` without its daemon, it
    shows what the router knows at that moment: an entity declared while the query is under
    way may be missing."""
    from launchkit.ros.graph import snapshot
    from launchkit.ros.session import client_config, close_session, open_session

    endpoint = use_router(args)
    with _connecting(endpoint):
        session = open_session(client_config(endpoint))
    try:
        return snapshot(session, domain_id(), timeout)
    finally:
        close_session(session)


@contextmanager
def _connecting(endpoint: str | None) -> Iterator[None]:
    """Turn Zenoh's failure to connect into a one-line error (the router went away)."""
    import zenoh

    try:
        yield
    except zenoh.ZError as error:
        shown = endpoint or router_endpoint(None)
        raise RuntimeLaunchError(f"cannot connect to the ROS router at {shown}: {error}") from None


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
