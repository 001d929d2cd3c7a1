"""``launchkit service list|call|type``: ros2 service's commands and output."""

from __future__ import annotations

import argparse
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros_cli.common import (
    CliUsageError,
    add_router_option,
    cli_node,
    graph_once,
    hidden_name,
    normalize_topic,
)


def add_parser(commands: Any) -> None:
    """Register the ``service`` subcommands."""
    service = commands.add_parser("service", help="services: list, call, type")
    sub = service.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="list services")
    p.add_argument("-t", "--show-types", action="store_true")
    p.add_argument("-a", "--include-hidden-services", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("call", help="call a service")
    p.add_argument("service_name")
    p.add_argument("service_type", help="e.g. std_srvs/srv/Trigger")
    p.add_argument("values", nargs="?", default="{}", help="the request as YAML")
    p.add_argument("--timeout", type=float, default=10.0, help="seconds to wait (10)")
    add_router_option(p)
    p.set_defaults(run=_call)
    p = sub.add_parser("type", help="a service's type")
    p.add_argument("service_name")
    add_router_option(p)
    p.set_defaults(run=_type)


def _services(args: argparse.Namespace, hidden: bool) -> dict[str, set[str]]:
    tokens = graph_once(args)
    services: dict[str, set[str]] = {}
    for t in tokens:
        if t.kind == "SS" and (hidden or not hidden_name(t.topic)):
            services.setdefault(t.topic, set()).add(t.type_name)
    return services


def _list(args: argparse.Namespace) -> int:
    services = _services(args, args.include_hidden_services)
    for name in sorted(services):
        suffix = f" [{', '.join(sorted(services[name]))}]" if args.show_types else ""
        print(f"{name}{suffix}")
    return 0


def _type(args: argparse.Namespace) -> int:
    name = normalize_topic(args.service_name)
    types = _services(args, True).get(name)
    if not types:
        raise CliUsageError(
            f"unknown service {name}", expected="a service listed by `launchkit service list`"
        )
    for type_name in sorted(types):
        print(type_name)
    return 0


def _call(args: argparse.Namespace) -> int:
    from launchkit.ros.message_data import from_yaml, short_repr
    from launchkit.ros.msgs import get_service
    from launchkit.ros.services import ServiceCallError

    srv = get_service(args.service_type)
    request = from_yaml(srv._TYPE_NAME + "_Request", args.values)
    name = normalize_topic(args.service_name)
    with cli_node(args) as node:
        client = node.create_client(srv, name)
        if not client.service_is_ready():
            print("waiting for service to become available...", flush=True)
            if not client.wait_for_service(timeout_sec=args.timeout):
                raise RuntimeLaunchError(
                    f"service {name} ({srv._TYPE_NAME}) did not become available "
                    f"in {args.timeout} s"
                )
        print(f"requester: making request: {short_repr(request)}\n", flush=True)
        try:
            response = client.call(request, timeout_sec=args.timeout)
        except ServiceCallError as exc:
            raise RuntimeLaunchError(str(exc)) from None
        if response is None:
            raise RuntimeLaunchError(f"service {name} did not answer in {args.timeout} s")
    print(f"response:\n{short_repr(response)}\n")
    return 0
