"""``launchkit topic list|echo|pub|hz|bw|info|type|find``: ros2 topic's verbs and output.

``list``, ``info``, ``type`` and ``find`` ask the router once and need no node (this module);
``echo``, ``pub``, ``hz`` and ``bw`` make a node and import the message types when they run
(``topic_echo``, ``topic_pub``, ``topic_rates``).
"""

from __future__ import annotations

import argparse
from typing import Any

from launchkit.ros.keyexpr import Token
from launchkit.ros_cli.common import (
    CliUsageError,
    add_router_option,
    graph_once,
    names_and_types,
    normalize_topic,
    print_names,
)
from launchkit.ros_cli.qos_options import add_qos_arguments


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("Expects a floating point number") from None
    if value <= 0.0:
        raise argparse.ArgumentTypeError("Value must be positive")
    return value


def _int_at_least(minimum: int) -> Any:
    """An argparse type: an integer of at least ``minimum``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = minimum - 1
        if value < minimum:
            raise argparse.ArgumentTypeError(f"value must be an integer >= {minimum}")
        return value

    return parse


_positive_int = _int_at_least(1)
_nonnegative_int = _int_at_least(0)


def _lazy(module: str, function: str) -> Any:
    """A command's ``run`` that imports its module only when it runs."""

    def run(args: argparse.Namespace) -> int:
        import importlib

        return int(getattr(importlib.import_module(module), function)(args))

    return run


def add_parser(commands: Any) -> None:
    """Register the ``topic`` verbs."""
    topic = commands.add_parser("topic", help="topics: list, echo, pub, hz, bw, info, type, find")
    sub = topic.add_subparsers(dest="verb", metavar="VERB", required=True)

    p = sub.add_parser("list", help="Output a list of available topics")
    p.add_argument("-t", "--show-types", action="store_true", help="show each topic's type")
    p.add_argument("-c", "--count-topics", action="store_true", help="only count them")
    p.add_argument("-a", "--include-hidden-topics", action="store_true")
    p.add_argument("-v", "--verbose", action="store_true", help="publishers and subscribers")
    add_router_option(p)
    p.set_defaults(run=_list)

    p = sub.add_parser("echo", help="Output messages from a topic")
    p.add_argument("topic_name")
    p.add_argument("message_type", nargs="?", help="e.g. std_msgs/msg/String (default: found)")
    add_qos_arguments(p, "subscribe", "sensor_data")
    p.add_argument("--csv", action="store_true", help="every field, comma-separated")
    p.add_argument("--field", help="a field to print, '.' between sub-fields (pose.position)")
    p.add_argument("--full-length", "-f", action="store_true", help="do not cut long arrays")
    p.add_argument("--truncate-length", "-l", type=_nonnegative_int, default=128)
    p.add_argument("--no-arr", action="store_true", help="do not print array fields")
    p.add_argument("--no-str", action="store_true", help="do not print string fields")
    p.add_argument("--flow-style", action="store_true", help="YAML in flow style")
    p.add_argument("--no-lost-messages", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--raw", action="store_true", help="the serialized (CDR) bytes")
    p.add_argument("--filter", dest="filter_expr", help="a Python expression of m to select")
    p.add_argument("--once", action="store_true", help="print one message and exit")
    p.add_argument(
        "--timeout",
        type=_positive_float,
        help="stop after this many seconds (also waiting for the topic to appear)",
    )
    p.add_argument("--include-message-info", "-i", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_lazy("launchkit.ros_cli.topic_echo", "echo"))

    p = sub.add_parser("pub", help="Publish a message to a topic")
    p.add_argument("topic_name")
    p.add_argument("message_type")
    values = p.add_mutually_exclusive_group()
    values.add_argument("values", nargs="?", default="{}", help="YAML, e.g. '{data: hello}'")
    values.add_argument("--stdin", action="store_true", help="read the values from stdin")
    p.add_argument("-r", "--rate", metavar="N", type=_positive_float, default=1.0)
    p.add_argument("-p", "--print", metavar="N", type=int, default=1, dest="print_nth")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("-1", "--once", action="store_true", help="publish one message and exit")
    mode.add_argument("-t", "--times", type=_nonnegative_int, default=0)
    p.add_argument("-w", "--wait-matching-subscriptions", type=_nonnegative_int, default=None)
    p.add_argument("--max-wait-time-secs", type=_positive_float, default=None)
    p.add_argument("--keep-alive", metavar="N", type=_positive_float, default=0.1)
    p.add_argument("-n", "--node-name", help="the publishing node's name")
    add_qos_arguments(p, "publish", "default")
    add_router_option(p)
    p.set_defaults(run=_lazy("launchkit.ros_cli.topic_pub", "pub"))

    p = sub.add_parser("hz", help="Print the average publishing rate to screen")
    p.add_argument("topic_name")
    p.add_argument("--window", "-w", dest="window_size", type=_positive_int, default=10000)
    p.add_argument("--filter", dest="filter_expr", help="only count messages m matching this")
    p.add_argument("--wall-time", dest="use_wtime", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_lazy("launchkit.ros_cli.topic_rates", "hz"))

    p = sub.add_parser("bw", help="Display bandwidth used by topic")
    p.add_argument("topic_name")
    p.add_argument("--window", "-w", type=_positive_int, default=100)
    add_router_option(p)
    p.set_defaults(run=_lazy("launchkit.ros_cli.topic_rates", "bw"))

    p = sub.add_parser("info", help="Print information about a topic")
    p.add_argument("topic_name")
    p.add_argument("-v", "--verbose", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_info)

    p = sub.add_parser("type", help="Print a topic's type")
    p.add_argument("topic_name")
    add_router_option(p)
    p.set_defaults(run=_type)

    p = sub.add_parser("find", help="Output a list of available topics of a given type")
    p.add_argument("topic_type")
    p.add_argument("-c", "--count-topics", action="store_true")
    p.add_argument("-a", "--include-hidden-topics", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_find)


def _topics(tokens: list[Token], hidden: bool) -> dict[str, list[str]]:
    return names_and_types(tokens, ("MP", "MS"), hidden)


def _list(args: argparse.Namespace) -> int:
    tokens = graph_once(args)
    topics = _topics(tokens, args.include_hidden_topics)
    if args.count_topics:
        print(len(topics))
        return 0
    if args.verbose:
        for kind, title, noun in (
            ("MP", "Published", "publisher"),
            ("MS", "Subscribed", "subscriber"),
        ):
            lines = [f"{title} topics:"]
            for name, types in topics.items():
                count = sum(t.kind == kind and t.topic == name for t in tokens)
                if count:
                    plural = "s" if count > 1 else ""
                    lines.append(f" * {name} [{', '.join(types)}] {count} {noun}{plural}")
            print("\n".join(lines) + "\n")
        return 0
    print_names(topics, args.show_types)
    return 0


def _find(args: argparse.Namespace) -> int:
    topics = _topics(graph_once(args), args.include_hidden_topics)
    found = {name: types for name, types in topics.items() if args.topic_type in types}
    if args.count_topics:
        print(len(found))
        return 0
    print_names(found, False)
    return 0


def _known_topic(args: argparse.Namespace) -> tuple[list[str], list[Token]]:
    """The types of the topic the user named, and its endpoints; a usage error if unknown."""
    topic = normalize_topic(args.topic_name)
    tokens = graph_once(args)
    types = _topics(tokens, True).get(topic)
    if not types:
        raise CliUsageError(
            f"unknown topic {topic}", expected="a topic listed by `launchkit topic list`"
        )
    return types, [t for t in tokens if t.topic == topic]


def _type(args: argparse.Namespace) -> int:
    types, _ = _known_topic(args)
    for name in types:
        print(name)
    return 0


def _info(args: argparse.Namespace) -> int:
    types, tokens = _known_topic(args)
    end = "\n\n" if args.verbose else "\n"
    # ros2 prints one type bare and several as a Python list
    print(f"Type: {types[0] if len(types) == 1 else types}", end=end)
    for kind, label in (("MP", "Publisher"), ("MS", "Subscription")):
        group = [t for t in tokens if t.kind == kind]
        print(f"{label} count: {len(group)}", end=end)
        if args.verbose:
            for token in group:
                print(
                    endpoint_text(token, "PUBLISHER" if kind == "MP" else "SUBSCRIPTION"), end=end
                )
    return 0


def endpoint_text(token: Token, endpoint_type: str) -> str:
    """One endpoint as rclpy's ``TopicEndpointInfo`` prints it (``topic info -v``)."""
    from launchkit.ros.qos import HistoryPolicy, QoSProfile

    qos = token.qos or QoSProfile(depth=10)
    gid = ".".join(f"{b:02x}" for b in token.gid)
    depth = (
        f"{qos.history.name} ({qos.depth})"
        if qos.history == HistoryPolicy.KEEP_LAST
        else qos.history.name
    )
    return "\n".join(
        [
            f"Node name: {token.node_name}",
            f"Node namespace: {token.namespace}",
            f"Topic type: {token.type_name}",
            f"Topic type hash: {token.type_hash}",
            f"Endpoint type: {endpoint_type}",
            f"GID: {gid}",
            "QoS profile:",
            f"  Reliability: {qos.reliability.name}",
            f"  History (Depth): {depth}",
            f"  Durability: {qos.durability.name}",
            # rmw_zenoh's keys carry the durations and liveliness too; launchkit's endpoints
            # always have the defaults, which rclpy prints as these
            "  Lifespan: Infinite",
            "  Deadline: Infinite",
            "  Liveliness: AUTOMATIC",
            "  Liveliness lease duration: Infinite",
        ]
    )
