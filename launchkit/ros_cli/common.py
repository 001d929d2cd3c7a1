"""What every ``launchkit topic|node|service|param|interface`` command shares."""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from launchkit.envvars import ROUTER
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.ros.action.names import action_of_feedback
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
def cli_node(args: argparse.Namespace, name: str | None = None) -> Iterator[Node]:
    """A node for one command (hidden unless ``name`` is given: ``topic pub -n NAME``), its
    context shut down afterwards."""
    from launchkit.ros.context import Context
    from launchkit.ros.node import Node

    use_router(args)
    context = Context(start_router=False, client=True)  # use_router decided already
    context.init([])
    try:
        with _connecting(context.router):
            node = Node(
                name or f"_launchkit_cli_{os.getpid()}",
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


def absolute_node_name(name: str) -> str:
    """A node name as the graph holds it (``talker`` -> ``/talker``)."""
    return name if name.startswith("/") else "/" + name


def names_and_types(
    tokens: Iterable[Token], kinds: tuple[str, ...], include_hidden: bool
) -> dict[str, list[str]]:
    """The topic (or service) names of the entities of ``kinds`` (``MP``, ``MS``, ``SS``,
    ``SC``) and the sorted types of each, sorted by name, as rcl's ``get_*_names_and_types``
    gives them; hidden names left out unless asked for."""
    found: dict[str, set[str]] = {}
    for t in tokens:
        if t.kind in kinds and (include_hidden or not hidden_name(t.topic)):
            found.setdefault(t.topic, set()).add(t.type_name)
    return {name: sorted(found[name]) for name in sorted(found)}


def print_names(found: dict[str, list[str]], show_types: bool) -> None:
    """One name a line, with ``[type, ...]`` after it when asked (``topic list -t``)."""
    for name, types in found.items():
        print(f"{name} [{', '.join(types)}]" if show_types else name)


# An action NAME is served on NAME/_action/{send_goal,cancel_goal,get_result} and published on
# NAME/_action/{feedback,status}; rcl_action finds actions by their feedback topic.
def action_names_and_types(tokens: Iterable[Token], role: str) -> dict[str, list[str]]:
    """The actions of ``tokens`` and their types, as rcl_action finds them: a ``server``
    publishes, a ``client`` subscribes to ``NAME/_action/feedback`` of type
    ``pkg/action/Name_FeedbackMessage``, which is action ``NAME`` of type ``pkg/action/Name``."""
    kind = "MP" if role == "server" else "MS"
    found: dict[str, set[str]] = {}
    for t in tokens:
        action = action_of_feedback(t.topic, t.type_name) if t.kind == kind else None
        if action is not None:
            found.setdefault(action[0], set()).add(action[1])
    return {name: sorted(found[name]) for name in sorted(found)}


def node_names(tokens: Iterable[Token], include_hidden: bool) -> list[str]:
    """The full names of the nodes of ``tokens`` (one per node, so a name twice when two
    nodes share it), sorted."""
    return sorted(t.node_fqn for t in tokens if t.kind == "NN" and visible(t, include_hidden))


#: seconds a named node may take to show up, as ros2's ``--timeout`` default (a fresh session
#: on a busy machine can answer its first queries with part of the graph)
NODE_WAIT = 3.0


def wait_for_node(
    node: Node, name: str, include_hidden: bool = True, timeout: float = NODE_WAIT
) -> None:
    """Return once node ``name`` is in the graph; a usage error if it is not after ``timeout``
    seconds (:data:`NODE_WAIT` at least)."""
    deadline = time.monotonic() + max(timeout, NODE_WAIT)
    while name not in node_names(graph_tokens(node), include_hidden):
        if time.monotonic() > deadline:
            raise CliUsageError(
                f"unknown node {name}", expected="a node listed by `launchkit node list`"
            )
        time.sleep(0.1)


def wait_for_topic_type(node: Node, topic: str, timeout: float | None) -> tuple[str, list[Token]]:
    """The type of ``topic`` from the graph, and the graph it was found in. Like ros2 topic
    hz, wait until something publishes or subscribes to it, saying so once (``timeout``
    seconds at most; None: as long as it takes)."""
    deadline = None if timeout is None else time.monotonic() + timeout
    warned = False
    while True:
        tokens = graph_tokens(node)
        types = names_and_types(tokens, ("MP", "MS"), True).get(topic, [])
        if len(types) == 1:
            return types[0], tokens
        if len(types) > 1:
            raise CliUsageError(
                f"topic {topic} has several types: {', '.join(types)}",
                expected="the message type as the second argument",
            )
        if deadline is not None and time.monotonic() > deadline:
            raise CliUsageError(
                f"could not determine the type of {topic}: nothing publishes or subscribes to it",
                expected="a topic from `launchkit topic list`, or the message type as argument",
            )
        if not warned:
            print(f"WARNING: topic [{topic}] does not appear to be published yet", flush=True)
            warned = True
        if not node.context.ok():
            raise KeyboardInterrupt
        time.sleep(0.1)


def message_filter(text: str) -> Callable[[Any], bool]:
    """``--filter EXPR`` of ``topic echo`` and ``topic hz``: a Python expression of ``m`` (the
    message), evaluated as ros2 evaluates it. It is the user's own command line, run with
    their own rights; a syntax error is a usage error."""
    try:
        code = compile(text, "--filter", "eval")
    except SyntaxError as error:
        raise CliUsageError(
            f"--filter {text!r}: {error.msg}", expected="a Python expression of m"
        ) from None

    def keep(m: Any) -> bool:
        try:
            return bool(eval(code, {}, {"m": m}))
        except Exception as error:  # the user's expression failed on this message
            raise CliUsageError(
                f"--filter {text!r}: {type(error).__name__}: {error}",
                expected="an expression of m, the message (or the field --field selects)",
            ) from None

    return keep
