"""``launchkit node list|info``: ros2 node's commands and output."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from launchkit.ros.keyexpr import Token
from launchkit.ros_cli.common import (
    CliUsageError,
    absolute_node_name,
    action_names_and_types,
    add_router_option,
    graph_once,
    hidden_name,
    names_and_types,
    node_names,
    visible,
)


def add_parser(commands: Any) -> None:
    """Register the ``node`` subcommands."""
    node = commands.add_parser("node", help="nodes: list, info")
    sub = node.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="Output a list of available nodes")
    p.add_argument("-a", "--all", action="store_true", help="include hidden nodes")
    p.add_argument("-c", "--count-nodes", action="store_true", help="only count them")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("info", help="Output information about a node")
    p.add_argument("node_name")
    p.add_argument(
        "--include-hidden",
        action="store_true",
        help="show hidden topics, services and actions (and find a hidden node)",
    )
    add_router_option(p)
    p.set_defaults(run=_info)


def _list(args: argparse.Namespace) -> int:
    # one line per node, as ros2 node list: two nodes of one name are two lines and a warning
    names = node_names(graph_once(args), args.all)
    if args.count_nodes:
        print(len(names))
        return 0
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
    ("Action Servers", "server"),
    ("Action Clients", "client"),
)


def _info(args: argparse.Namespace) -> int:
    wanted = absolute_node_name(args.node_name)
    tokens = [t for t in graph_once(args) if t.node_fqn == wanted]
    # as ros2 node info: a hidden node (its name starts with "_") is found only when asked for
    count = sum(t.kind == "NN" and visible(t, args.include_hidden) for t in tokens)
    if not count:
        if any(t.kind == "NN" for t in tokens):
            raise CliUsageError(
                f"{wanted} is a hidden node", expected="--include-hidden to show hidden nodes"
            )
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
        # ros2 prints the entries one per line, or one empty line when there are none
        print("\n".join(info_lines(tokens, kind, args.include_hidden)))
    return 0


def info_lines(tokens: list[Token], kind: str, include_hidden: bool) -> list[str]:
    """The lines of one ``node info`` section: ``    NAME: TYPE[, TYPE]`` for the entities of
    ``kind`` (``MS``, ``MP``, ``SS``, ``SC``, or the actions a ``server`` or ``client`` has)."""
    if kind in ("server", "client"):
        entries = action_names_and_types(tokens, kind)
    else:
        entries = names_and_types(tokens, (kind,), True)
    return [
        f"    {name}: {', '.join(types)}"
        for name, types in entries.items()
        if include_hidden or not hidden_name(name)
    ]
