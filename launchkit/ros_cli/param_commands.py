"""``launchkit param list|get|set|describe|dump|load|delete``: a node's parameters through its
parameter services, printed as ``ros2 param`` prints them."""

from __future__ import annotations

import argparse
import re
import sys
from typing import Any

from launchkit.ros_cli.common import (
    CliUsageError,
    absolute_node_name,
    add_router_option,
    cli_node,
    graph_tokens,
    node_names,
    wait_for_node,
)
from launchkit.ros_cli.parameter_values import (
    TYPE_NAMES,
    NoParameterServices,
    ParameterClient,
    python_value,
    value_from_text,
)

_LABELS = {
    1: "Boolean value is:",
    2: "Integer value is:",
    3: "Double value is:",
    4: "String value is:",
    5: "Byte values are:",
    6: "Boolean values are:",
    7: "Integer values are:",
    8: "Double values are:",
    9: "String values are:",
}


def add_parser(commands: Any) -> None:
    """Register the ``param`` verbs."""
    param = commands.add_parser(
        "param", help="parameters: list, get, set, describe, dump, load, delete"
    )
    sub = param.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="Output a list of available parameters")
    p.add_argument("node_name", nargs="?")
    p.add_argument("--filter", help="only the names this regular expression matches")
    p.add_argument("--param-prefixes", nargs="+", default=[])
    p.add_argument("--param-type", action="store_true", help="print each parameter's type")
    _common(p, _list)
    p = _node_verb(sub, "get", "Get parameter", _get)
    p.add_argument("parameter_name")
    p.add_argument("--hide-type", action="store_true", help="print the value alone")
    p = _node_verb(sub, "set", "Set parameter", _set)
    p.add_argument("parameter_name")
    p.add_argument("value", help="read as YAML, as ros2 param set reads it")
    p = _node_verb(sub, "describe", "Show descriptive information about parameters", _describe)
    p.add_argument("parameter_names", nargs="+")
    p = _node_verb(sub, "dump", "Show all of the parameters of a node as YAML", _dump)
    p.add_argument(
        "--output-dir", help="write NODE.yaml there instead (deprecated in ros2: use > FILE)"
    )
    p = _node_verb(sub, "load", "Load parameter file for a node", _load)
    p.add_argument("parameter_file")
    p.add_argument("--no-use-wildcard", action="store_true", help="leave out the '/**' entries")
    p = _node_verb(sub, "delete", "Delete parameter", _delete)
    p.add_argument("parameter_name")


def _node_verb(sub: Any, name: str, help_text: str, run: Any) -> argparse.ArgumentParser:
    parser: argparse.ArgumentParser = sub.add_parser(name, help=help_text)
    parser.add_argument("node_name")
    _common(parser, run)
    return parser


def _common(parser: argparse.ArgumentParser, run: Any) -> None:
    parser.add_argument("--include-hidden-nodes", action="store_true")
    parser.add_argument(
        "--timeout",
        metavar="N",
        type=int,
        default=1,
        help="wait up to N seconds for the node to appear (at least 3)",
    )
    add_router_option(parser)
    parser.set_defaults(run=run)


def _list(args: argparse.Namespace) -> int:
    pattern = re.compile(args.filter) if args.filter else None
    with cli_node(args) as node:
        if args.node_name:
            targets = [absolute_node_name(args.node_name)]
            wait_for_node(node, targets[0], args.include_hidden_nodes, args.timeout)
        else:
            targets = sorted(set(node_names(graph_tokens(node), args.include_hidden_nodes)))
        for target in targets:
            client = ParameterClient(node, target)
            try:
                names = sorted(client.names(args.param_prefixes))
            except NoParameterServices as missing:  # said, and the next node listed
                print(missing.format().removeprefix("error: "))
                continue
            if pattern is not None:
                names = [name for name in names if pattern.match(name)]
            if not args.node_name and names:
                print(f"{target}:")
            types = client.types(names) if args.param_type else {}
            for name in names:
                print(f"  {name} (type: {types[name]})" if args.param_type else f"  {name}")
    return 0


def _target(args: argparse.Namespace, node: Any) -> ParameterClient:
    target = absolute_node_name(args.node_name)
    wait_for_node(node, target, args.include_hidden_nodes, args.timeout)
    return ParameterClient(node, target)


def _get(args: argparse.Namespace) -> int:
    with cli_node(args) as node:
        values = _target(args, node).get([args.parameter_name])
    if not values:
        raise CliUsageError(
            f"Parameter not set: {args.parameter_name!r} on {absolute_node_name(args.node_name)}",
            expected=f"one of the names `launchkit param list {args.node_name}` shows",
        )
    value = values[0]
    label = _LABELS.get(value.type, "Parameter not set.")
    shown = python_value(value)
    if args.hide_type:
        print(shown)
    elif shown is None:
        print(label)
    else:
        print(label, shown)
    return 0


def _set(args: argparse.Namespace) -> int:
    with cli_node(args) as node:
        result = _target(args, node).set({args.parameter_name: value_from_text(args.value)})[0]
    return _say(result, "Set parameter successful", "Setting parameter failed")


def _delete(args: argparse.Namespace) -> int:
    with cli_node(args) as node:
        result = _target(args, node).set({args.parameter_name: value_from_text(None)})[0]
    return _say(result, "Deleted parameter successfully", "Deleting parameter failed")


def _say(result: Any, success: str, failure: str) -> int:
    """ros2 param's line for one SetParametersResult (a failure on stderr, exit status 1)."""
    reason = f": {result.reason}" if result.reason else ""
    if result.successful:
        print(success + reason)
        return 0
    print(failure + reason, file=sys.stderr)
    return 1


def _describe(args: argparse.Namespace) -> int:
    with cli_node(args) as node:
        descriptors = _target(args, node).describe(args.parameter_names)
    for descriptor in descriptors:
        print("Parameter name:", descriptor.name)
        print("  Type:", TYPE_NAMES.get(descriptor.type, "not set"))
        if descriptor.description:
            print("  Description:", descriptor.description)
        print("  Constraints:")
        if descriptor.read_only:
            print("    Read only: true")
        ranges = [*descriptor.floating_point_range, *descriptor.integer_range]
        if ranges:
            print("    Min value:", ranges[0].from_value)
            print("    Max value:", ranges[0].to_value)
            if ranges[0].step:
                print("    Step:", ranges[0].step)
        if descriptor.additional_constraints:
            print("    Additional constraints:", descriptor.additional_constraints)
    return 0


def _dump(args: argparse.Namespace) -> int:
    from launchkit.ros_cli.parameter_files import dump_text, write_dump

    target = absolute_node_name(args.node_name)
    with cli_node(args) as node:
        client = _target(args, node)
        names = sorted(client.names([]))
        values = client.get(names) if names else []
    text = dump_text(target, {n: python_value(v) for n, v in zip(names, values, strict=False)})
    if args.output_dir is None:
        print(text)
        return 0
    print(
        "WARNING: '--output-dir' is deprecated; use redirection to save to a file", file=sys.stderr
    )
    print("Saving to: ", write_dump(args.output_dir, target, text))
    return 0


def _load(args: argparse.Namespace) -> int:
    from launchkit.ros_cli.parameter_files import parameters_in_file

    target = absolute_node_name(args.node_name)
    parameters = parameters_in_file(args.parameter_file, target, not args.no_use_wildcard)
    with cli_node(args) as node:
        results = _target(args, node).set(parameters)
    status = 0
    for name, result in zip(parameters, results, strict=True):
        status |= _say(result, f"Set parameter {name} successful", f"Set parameter {name} failed")
    return status
