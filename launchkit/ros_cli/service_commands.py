"""``launchkit service list|type|find|call``: ros2 service's verbs and output."""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros_cli.common import (
    CliUsageError,
    add_router_option,
    cli_node,
    graph_once,
    names_and_types,
    normalize_topic,
    print_names,
)

_GRAPH_SETTLES = 1.0  # seconds


def add_parser(commands: Any) -> None:
    """Register the ``service`` verbs."""
    service = commands.add_parser("service", help="services: list, type, find, call")
    sub = service.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="Output a list of available services")
    p.add_argument("-t", "--show-types", action="store_true")
    p.add_argument("-c", "--count-services", action="store_true")
    p.add_argument("-a", "--include-hidden-services", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("type", help="Output a service's type")
    p.add_argument("service_name")
    add_router_option(p)
    p.set_defaults(run=_type)
    p = sub.add_parser("find", help="Output a list of available services of a given type")
    p.add_argument("service_type")
    p.add_argument("-c", "--count-services", action="store_true")
    p.add_argument("-a", "--include-hidden-services", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_find)
    p = sub.add_parser("call", help="Call a service")
    p.add_argument("service_name")
    p.add_argument("service_type", help="e.g. std_srvs/srv/Trigger")
    values = p.add_mutually_exclusive_group()
    values.add_argument("values", nargs="?", default="{}", help="the request as YAML")
    values.add_argument("--stdin", action="store_true", help="read the request from stdin")
    p.add_argument("-r", "--rate", metavar="N", type=float, help="repeat the call N times a second")
    p.add_argument(
        "--timeout",
        type=float,
        help="seconds to wait for the service and for each answer (default: as long as it takes)",
    )
    add_router_option(p)
    p.set_defaults(run=_call)


def _services(args: argparse.Namespace, hidden: bool) -> dict[str, list[str]]:
    return names_and_types(graph_once(args), ("SS",), hidden)


def _list(args: argparse.Namespace) -> int:
    services = _services(args, args.include_hidden_services)
    if args.count_services:
        print(len(services))
        return 0
    print_names(services, args.show_types)
    return 0


def _find(args: argparse.Namespace) -> int:
    services = _services(args, args.include_hidden_services)
    found = {name: types for name, types in services.items() if args.service_type in types}
    if args.count_services:
        print(len(found))
        return 0
    print_names(found, False)
    return 0


def _type(args: argparse.Namespace) -> int:
    name = normalize_topic(args.service_name)
    types = _services(args, True).get(name)
    if not types:
        raise CliUsageError(
            f"unknown service {name}", expected="a service listed by `launchkit service list`"
        )
    for type_name in types:
        print(type_name)
    return 0


def _call(args: argparse.Namespace) -> int:
    from launchkit.ros.message_data import from_yaml
    from launchkit.ros.message_text import short_repr
    from launchkit.ros.msgs import get_service
    from launchkit.ros.services import ServiceCallError

    if args.rate is not None and args.rate <= 0:
        raise CliUsageError("rate must be greater than zero", expected="-r N with N > 0")
    srv = get_service(args.service_type)
    text = sys.stdin.read() if args.stdin else args.values
    request = from_yaml(srv._TYPE_NAME + "_Request", text)
    name = normalize_topic(args.service_name)
    with cli_node(args) as node:
        client = node.create_client(srv, name)
        # a fresh node learns the graph in a moment: say "waiting" only when that was not it
        if not client.wait_for_service(timeout_sec=_GRAPH_SETTLES):
            print("waiting for service to become available...", flush=True)
            if not client.wait_for_service(timeout_sec=args.timeout):
                if not node.context.ok():  # Ctrl-C while waiting
                    raise KeyboardInterrupt
                raise RuntimeLaunchError(
                    f"service {name} ({srv._TYPE_NAME}) did not become available "
                    f"in {args.timeout} s"
                )
        while True:
            started = time.monotonic()
            print(f"requester: making request: {short_repr(request)}\n", flush=True)
            try:
                response = client.call(request, timeout_sec=args.timeout)
            except ServiceCallError as exc:
                raise RuntimeLaunchError(f"Exception while calling service: {exc}") from None
            if response is None:
                raise RuntimeLaunchError(f"service {name} did not answer in {args.timeout} s")
            print(f"response:\n{short_repr(response)}\n", flush=True)
            if args.rate is None or not node.context.ok():
                break
            time.sleep(max(0.0, started + 1.0 / args.rate - time.monotonic()))
    return 0
