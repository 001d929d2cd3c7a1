"""``launchkit param list|get|set``: a node's parameters through its parameter services."""

from __future__ import annotations

import argparse
import time
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros.msgs import get_message, get_service
from launchkit.ros.node import Node
from launchkit.ros.params import Parameter, ParameterType, parameter_from_value, parse_value_text
from launchkit.ros_cli.common import CliUsageError, add_router_option, cli_node, graph_tokens

_LABELS = {
    ParameterType.BOOL: "Boolean value is",
    ParameterType.INTEGER: "Integer value is",
    ParameterType.DOUBLE: "Double value is",
    ParameterType.STRING: "String value is",
    ParameterType.BYTE_ARRAY: "Byte values are",
    ParameterType.BOOL_ARRAY: "Boolean values are",
    ParameterType.INTEGER_ARRAY: "Integer values are",
    ParameterType.DOUBLE_ARRAY: "Double values are",
    ParameterType.STRING_ARRAY: "String values are",
}


def add_parser(commands: Any) -> None:
    """Register the ``param`` subcommands."""
    param = commands.add_parser("param", help="parameters: list, get, set")
    sub = param.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="list the parameters of one node or of every node")
    p.add_argument("node_name", nargs="?")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("get", help="print a parameter's value")
    p.add_argument("node_name")
    p.add_argument("parameter_name")
    add_router_option(p)
    p.set_defaults(run=_get)
    p = sub.add_parser("set", help="set a parameter (the value is read as YAML)")
    p.add_argument("node_name")
    p.add_argument("parameter_name")
    p.add_argument("value")
    add_router_option(p)
    p.set_defaults(run=_set)


def _fqn(name: str) -> str:
    return name if name.startswith("/") else "/" + name


def _call(node: Node, target: str, srv_name: str, request: Any) -> Any:
    srv = get_service(f"rcl_interfaces/srv/{srv_name}")
    service = f"{target}/{_snake(srv_name)}"
    client = node.create_client(srv, service)
    if not client.wait_for_service(timeout_sec=5.0):
        raise CliUsageError(
            f"node {target} has no parameter services",
            expected="a running node (see `launchkit node list`)",
        )
    try:
        response = client.call(request, timeout_sec=10.0)
    except Exception as exc:
        raise RuntimeLaunchError(f"{service}: {exc}") from None
    if response is None:
        raise RuntimeLaunchError(f"{service}: no answer within 10 s")
    return response


def _snake(name: str) -> str:
    return "".join("_" + c.lower() if c.isupper() else c for c in name).lstrip("_")


def _known_nodes(node: Node) -> list[str]:
    return sorted(
        {
            t.node_fqn
            for t in graph_tokens(node)
            if t.kind == "NN" and not t.node_name.startswith("_")
        }
    )


_NODE_WAIT = 3.0  # seconds a named node may take to show up in a fresh session's graph


def _require_node(node: Node, target: str) -> None:
    # A busy machine can answer the first graph queries with part of the graph: a node the user
    # names is looked for again until it shows up or _NODE_WAIT has passed.
    deadline = time.monotonic() + _NODE_WAIT
    while target not in _known_nodes(node):
        if time.monotonic() < deadline:
            time.sleep(0.1)
            continue
        raise CliUsageError(
            f"unknown node {target}", expected="a node listed by `launchkit node list`"
        )


def _list(args: argparse.Namespace) -> int:
    srv = get_service("rcl_interfaces/srv/ListParameters")
    with cli_node(args) as node:
        if args.node_name:
            targets = [_fqn(args.node_name)]
            _require_node(node, targets[0])
        else:
            targets = _known_nodes(node)
        for target in targets:
            response = _call(node, target, "ListParameters", srv.Request())
            print(f"{target}:")
            for name in sorted(response.result.names):
                print(f"  {name}")
    return 0


def _get(args: argparse.Namespace) -> int:
    srv = get_service("rcl_interfaces/srv/GetParameters")
    target = _fqn(args.node_name)
    with cli_node(args) as node:
        _require_node(node, target)
        response = _call(node, target, "GetParameters", srv.Request(names=[args.parameter_name]))
    value = Parameter(args.parameter_name, ParameterType.NOT_SET)
    if response.values:  # none at all for an undeclared name, as rclpy answers
        value = Parameter.from_msg_value(args.parameter_name, response.values[0])
    if value.type_ == ParameterType.NOT_SET:
        raise CliUsageError(
            f"parameter {args.parameter_name!r} is not set on {target}",
            expected=f"one of the names `launchkit param list {target}` shows",
        )
    shown = value.value
    if value.type_ == ParameterType.BOOL:
        shown = "True" if shown else "False"
    print(f"{_LABELS[value.type_]}: {shown}")
    return 0


def _set(args: argparse.Namespace) -> int:
    srv = get_service("rcl_interfaces/srv/SetParameters")
    target = _fqn(args.node_name)
    param = parameter_from_value(args.parameter_name, parse_value_text(args.value))
    msg = get_message("rcl_interfaces/msg/Parameter")(
        name=args.parameter_name, value=param.to_msg_value()
    )
    with cli_node(args) as node:
        _require_node(node, target)
        response = _call(node, target, "SetParameters", srv.Request(parameters=[msg]))
    result = response.results[0]
    if result.successful:
        print("Set parameter successful")
        return 0
    print(f"Setting parameter failed: {result.reason}")
    return 1
