"""``launchkit node list|info``: ros2 node's commands and output."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from launchkit.ros_cli.common import (
    CliUsageError,
    add_router_option,
    graph_once,
    visible,
)


def add_parser(commands: Any) -> None:
    """Register the ``node`` subcommands."""
    node = commands.add_parser("node", help="nodes: list, info")
    sub = node.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="list running nodes")
    p.add_argument("-a", "--all", action="store_true", help="include hidden nodes")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("info", help="a node's publishers, subscriptions and services")
    p.add_argument("node_name")
    add_router_option(p)
    p.set_defaults(run=_info)


def _list(args: argparse.Namespace) -> int:
    # one line per node, as ros2 node list: two nodes of one name are two lines and a warning
    names = sorted(t.node_fqn for t in graph_once(args) if t.kind == "NN" and visible(t, args.all))
    if len(set(names)) < len(names):
        twice = sorted({name for name in names if names.count(name) > 1})
        print(
            f"WARNING: more than one node in the graph is named {', '.join(twice)}: tools reach "
            "only one of them, and they share parameters and logs",
            file=sys.stderr,
        )
    for name in names:
        print(name)
    return 0


_SECTIONS = (
    ("Subscribers", "MS"),
    ("Publishers", "MP"),
    ("Service Servers", "SS"),
    ("Service Clients", "SC"),
)


def _info(args: argparse.Namespace) -> int:
    wanted = args.node_name if args.node_name.startswith("/") else "/" + args.node_name
    tokens = [t for t in graph_once(args) if t.node_fqn == wanted]
    count = sum(t.kind == "NN" for t in tokens)
    if not count:
        raise CliUsageError(
            f"unknown node {wanted}", expected="a node listed by `launchkit node list`"
        )
    if count > 1:
        print(
            f"WARNING: {count} nodes in the graph are named {wanted}: what follows is all of "
            "theirs together",
            file=sys.stderr,
        )
    print(wanted)
    for title, kind in _SECTIONS:
        print(f"  {title}:")
        entries = sorted({(t.topic, t.type_name) for t in tokens if t.kind == kind})
        for name, type_name in entries:
            print(f"    {name}: {type_name}")
        if not entries:
            print()
    print("  Action Servers:\n\n  Action Clients:\n")
    return 0
