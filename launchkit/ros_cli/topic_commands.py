"""``launchkit topic list|echo|pub|hz|info|type``: ros2 topic's commands and output."""

from __future__ import annotations

import argparse
import itertools
import math
import sys
import threading
import time
from typing import Any

from launchkit.ros.keyexpr import Token
from launchkit.ros.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from launchkit.ros_cli.common import (
    CliUsageError,
    add_router_option,
    cli_node,
    graph_once,
    graph_tokens,
    hidden_name,
    normalize_topic,
)

# list, info and type ask the router once and need no node; echo, pub and hz import the message
# types (and numpy) when they run


def add_parser(commands: Any) -> None:
    """Register the ``topic`` subcommands."""
    topic = commands.add_parser("topic", help="topics: list, echo, pub, hz, info, type")
    sub = topic.add_subparsers(dest="verb", metavar="VERB", required=True)

    p = sub.add_parser("list", help="list topics")
    p.add_argument("-t", "--show-types", action="store_true", help="show each topic's type")
    p.add_argument("-a", "--include-hidden-topics", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_list)

    p = sub.add_parser("echo", help="print the messages on a topic as YAML")
    p.add_argument("topic_name")
    p.add_argument("message_type", nargs="?", help="e.g. std_msgs/msg/String (default: discovered)")
    p.add_argument("--once", action="store_true", help="print one message and exit")
    p.add_argument("--full-length", "-f", action="store_true", help="do not cut long arrays")
    p.add_argument(
        "--timeout",
        type=float,
        help="seconds to wait for the topic to appear (default: as long as it takes)",
    )
    add_router_option(p)
    p.set_defaults(run=_echo)

    p = sub.add_parser("pub", help="publish a message")
    p.add_argument("topic_name")
    p.add_argument("message_type")
    p.add_argument("values", nargs="?", default="{}", help="YAML, e.g. '{data: hello}'")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("-1", "--once", action="store_true", help="publish one message and exit")
    mode.add_argument("-t", "--times", type=int, help="publish this many messages and exit")
    p.add_argument("-r", "--rate", type=float, default=1.0, help="messages per second (1)")
    p.add_argument("-w", "--wait-matching-subscriptions", type=int, default=None)
    add_router_option(p)
    p.set_defaults(run=_pub)

    p = sub.add_parser("hz", help="print the rate of a topic")
    p.add_argument("topic_name")
    p.add_argument("-w", "--window", type=int, default=10000)
    add_router_option(p)
    p.set_defaults(run=_hz)

    p = sub.add_parser("info", help="a topic's type and endpoints")
    p.add_argument("topic_name")
    p.add_argument("-v", "--verbose", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_info)

    p = sub.add_parser("type", help="a topic's type")
    p.add_argument("topic_name")
    add_router_option(p)
    p.set_defaults(run=_type)


def _topics(tokens: list[Token], hidden: bool) -> dict[str, set[str]]:
    topics: dict[str, set[str]] = {}
    for t in tokens:
        if t.kind in ("MP", "MS") and (hidden or not hidden_name(t.topic)):
            topics.setdefault(t.topic, set()).add(t.type_name)
    return topics


def _list(args: argparse.Namespace) -> int:
    topics = _topics(graph_once(args), args.include_hidden_topics)
    for name in sorted(topics):
        suffix = f" [{', '.join(sorted(topics[name]))}]" if args.show_types else ""
        print(f"{name}{suffix}")
    return 0


def _discover_type(node: Any, topic: str, timeout: float | None) -> tuple[str, list[Token]]:
    """The type of ``topic`` from the graph, and the graph it was found in; like ros2, wait
    until something publishes or subscribes to it, saying so once (``timeout`` seconds at most;
    None: as long as it takes)."""
    deadline = None if timeout is None else time.monotonic() + timeout
    warned = False
    while True:
        tokens = graph_tokens(node)
        types = _topics(tokens, True).get(topic, set())
        if len(types) == 1:
            return types.pop(), tokens
        if len(types) > 1:
            raise CliUsageError(
                f"topic {topic} has several types: {', '.join(sorted(types))}",
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


def _echo_qos(tokens: list[Token], topic: str) -> QoSProfile:
    publishers = [t.qos for t in tokens if t.kind == "MP" and t.topic == topic and t.qos]
    best_effort = any(q.reliability == ReliabilityPolicy.BEST_EFFORT for q in publishers)
    latched = bool(publishers) and all(
        q.durability == DurabilityPolicy.TRANSIENT_LOCAL for q in publishers
    )
    return QoSProfile(
        depth=10,
        reliability=ReliabilityPolicy.BEST_EFFORT if best_effort else ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
    )


def _echo(args: argparse.Namespace) -> int:
    from launchkit.ros.message_data import to_yaml
    from launchkit.ros.msgs import get_message, normalize_type_name

    topic = normalize_topic(args.topic_name)
    given = args.message_type
    msg_class = get_message(given) if given else None
    with cli_node(args) as node:
        if given:
            type_name, tokens = normalize_type_name(given), graph_tokens(node)
        else:
            type_name, tokens = _discover_type(node, topic, args.timeout)
        msg_class = msg_class or get_message(type_name)
        truncate = None if args.full_length else 128
        done = threading.Event()

        def show(msg: Any) -> None:
            sys.stdout.write(to_yaml(msg, truncate) + "---\n")
            sys.stdout.flush()
            if args.once:
                done.set()

        node.create_subscription(msg_class, topic, show, _echo_qos(tokens, topic))
        _spin_until(node, done)
    return 0


def _spin_until(node: Any, done: threading.Event) -> None:
    from launchkit.ros.executor import spin_once

    while not done.is_set() and node.context.ok():
        spin_once(node, timeout_sec=0.1)


def _pub(args: argparse.Namespace) -> int:
    from launchkit.ros.clock import Clock, ClockType
    from launchkit.ros.message_data import from_yaml
    from launchkit.ros.msgs import get_message
    from launchkit.ros.rate import Rate

    topic = normalize_topic(args.topic_name)
    msg_class = get_message(args.message_type)
    msg = from_yaml(msg_class._TYPE_NAME, args.values)
    if args.rate <= 0:
        raise CliUsageError(
            f"invalid rate {args.rate}", expected="a rate > 0 (messages per second)"
        )
    times = 1 if args.once else args.times
    with cli_node(args) as node:
        pub = node.create_publisher(msg_class, topic, 10)
        wanted = args.wait_matching_subscriptions
        if wanted is None:
            wanted = 1 if times else 0
        if wanted:
            # like ros2: give subscribers a moment to match so a --once message is not lost
            pub.wait_for_subscriptions(wanted, timeout_sec=2.0)
        print("publisher: beginning loop")
        rate = Rate(args.rate, Clock(clock_type=ClockType.STEADY_TIME), context=node.context)
        count = 0
        while True:
            count += 1
            print(f"publishing #{count}: {_one_line(msg)}\n", flush=True)
            pub.publish(msg)
            if times is not None and count >= times:
                break
            rate.sleep()
        if times is not None:
            _linger(pub)
    return 0


def _linger(pub: Any) -> None:
    # put() hands the sample to zenoh's threads and closing the session drops what is still
    # queued: give the last message a moment to leave before the command exits
    time.sleep(0.1)


def _one_line(msg: Any) -> str:
    from launchkit.ros.message_data import short_repr

    return short_repr(msg)


def _hz(args: argparse.Namespace) -> int:
    from launchkit.ros.msgs import get_message

    topic = normalize_topic(args.topic_name)
    with cli_node(args) as node:
        type_name, tokens = _discover_type(node, topic, None)
        stamps: list[float] = []
        lock = threading.Lock()

        def on_message(_: bytes) -> None:
            with lock:
                stamps.append(time.monotonic())
                del stamps[: -args.window - 1]

        node.create_subscription(
            get_message(type_name),
            topic,
            on_message,
            _echo_qos(tokens, topic),
            raw=True,
        )
        next_report = time.monotonic() + 1.0
        from launchkit.ros.executor import spin_once

        while node.context.ok():
            spin_once(node, timeout_sec=max(0.0, next_report - time.monotonic()))
            if time.monotonic() >= next_report:
                next_report += 1.0
                with lock:
                    print(_rate_report(stamps), flush=True)
    return 0


def _rate_report(stamps: list[float]) -> str:
    if len(stamps) < 2:
        return "no new messages"
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    mean = sum(gaps) / len(gaps)
    std = math.sqrt(sum((g - mean) ** 2 for g in gaps) / len(gaps))
    return (
        f"average rate: {1.0 / mean:.3f}\n"
        f"\tmin: {min(gaps):.3f}s max: {max(gaps):.3f}s std dev: {std:.5f}s window: {len(stamps)}"
    )


def _info(args: argparse.Namespace) -> int:
    topic = normalize_topic(args.topic_name)
    tokens = [t for t in graph_once(args) if t.topic == topic and t.kind in ("MP", "MS")]
    if not tokens:
        raise CliUsageError(
            f"unknown topic {topic}", expected="a topic listed by `launchkit topic list`"
        )
    types = sorted({t.type_name for t in tokens})
    pubs = [t for t in tokens if t.kind == "MP"]
    subs = [t for t in tokens if t.kind == "MS"]
    print(f"Type: {'; '.join(types)}\n")
    for label, group in (("Publisher", pubs), ("Subscription", subs)):
        print(f"{label} count: {len(group)}\n")
        if args.verbose:
            for t in group:
                print(_endpoint(t, label))
    return 0


def _endpoint(t: Token, label: str) -> str:
    qos = t.qos or QoSProfile(depth=10)
    gid = ".".join(f"{b:02x}" for b in t.gid)
    return (
        f"Node name: {t.node_name}\n"
        f"Node namespace: {t.namespace}\n"
        f"Topic type: {t.type_name}\n"
        f"Topic type hash: {t.type_hash}\n"
        f"Endpoint type: {label.upper()}\n"
        f"GID: {gid}\n"
        f"QoS profile:\n"
        f"  Reliability: {qos.reliability.name}\n"
        f"  History (Depth): {qos.history.name} ({qos.depth})\n"
        f"  Durability: {qos.durability.name}\n"
    )


def _type(args: argparse.Namespace) -> int:
    topic = normalize_topic(args.topic_name)
    types = _topics(graph_once(args), True).get(topic)
    if not types:
        raise CliUsageError(
            f"unknown topic {topic}", expected="a topic listed by `launchkit topic list`"
        )
    for name in sorted(types):
        print(name)
    return 0
