"""``launchkit action list|info|send_goal``: ros2 action's verbs and output."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from launchkit.ros_cli.common import (
    CliUsageError,
    action_names_and_types,
    add_router_option,
    cli_node,
    graph_once,
    normalize_topic,
    print_names,
)

#: ros2 action send_goal's words for a goal's final status (action_msgs/msg/GoalStatus)
_STATUS = {
    1: "ACCEPTED",
    2: "EXECUTING",
    3: "CANCELING",
    4: "SUCCEEDED",
    5: "CANCELED",
    6: "ABORTED",
}


def add_parser(commands: Any) -> None:
    """Register the ``action`` verbs."""
    action = commands.add_parser("action", help="actions: list, info, send_goal")
    sub = action.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser("list", help="Output a list of action names")
    p.add_argument("-t", "--show-types", action="store_true")
    p.add_argument("-c", "--count-actions", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_list)
    p = sub.add_parser("info", help="Print information about an action")
    p.add_argument("action_name")
    p.add_argument("-t", "--show-types", action="store_true")
    p.add_argument("-c", "--count", action="store_true")
    add_router_option(p)
    p.set_defaults(run=_info)
    p = sub.add_parser("send_goal", help="Send an action goal")
    p.add_argument("action_name")
    p.add_argument("action_type", help="e.g. example_interfaces/action/Fibonacci")
    goal = p.add_mutually_exclusive_group()
    goal.add_argument("goal", nargs="?", default="{}", help="the goal as YAML, e.g. '{order: 5}'")
    goal.add_argument("--stdin", action="store_true", help="read the goal from stdin")
    p.add_argument("-f", "--feedback", action="store_true", help="echo the goal's feedback")
    add_router_option(p)
    p.set_defaults(run=_send_goal)


def _list(args: argparse.Namespace) -> int:
    tokens = graph_once(args)
    found: dict[str, set[str]] = {}
    for role in ("server", "client"):
        for name, types in action_names_and_types(tokens, role).items():
            found.setdefault(name, set()).update(types)
    actions = {name: sorted(found[name]) for name in sorted(found)}
    if args.count_actions:
        print(len(actions))
        return 0
    print_names(actions, args.show_types)
    return 0


def _info(args: argparse.Namespace) -> int:
    name = normalize_topic(args.action_name)
    tokens = graph_once(args)
    nodes = sorted({(t.namespace, t.node_name) for t in tokens if t.kind == "NN"})
    print(f"Action: {args.action_name}")
    for title, role in (("Action clients", "client"), ("Action servers", "server")):
        found = []
        for namespace, node_name in nodes:
            own = [t for t in tokens if (t.namespace, t.node_name) == (namespace, node_name)]
            types = action_names_and_types(own, role).get(name)
            if types is not None:
                found.append((f"{namespace.rstrip('/')}/{node_name}", types))
        print(f"{title}: {len(found)}")
        if not args.count:
            for node_fqn, types in found:
                print(
                    f"    {node_fqn} [{', '.join(types)}]" if args.show_types else f"    {node_fqn}"
                )
    return 0


def _send_goal(args: argparse.Namespace) -> int:
    from launchkit.ros.action import ActionClient
    from launchkit.ros.executors import SingleThreadedExecutor
    from launchkit.ros.message_data import from_yaml
    from launchkit.ros.message_text import to_yaml
    from launchkit.ros.msgs import get_action

    try:
        action = get_action(args.action_type)
    except (KeyError, ValueError):
        raise CliUsageError(
            f"unknown action type {args.action_type!r}",
            expected="pkg/action/Name (see `launchkit interface list -a`)",
        ) from None
    goal = from_yaml(args.action_type + "_Goal", sys.stdin.read() if args.stdin else args.goal)

    def on_feedback(message: Any) -> None:
        print(f"Feedback:\n    {to_yaml(message.feedback)}", flush=True)

    with cli_node(args) as node:
        executor = SingleThreadedExecutor(context=node.context)
        executor.add_node(node)
        client = ActionClient(node, action, normalize_topic(args.action_name))
        print("Waiting for an action server to become available...", flush=True)
        client.wait_for_server()
        if not node.context.ok():
            raise KeyboardInterrupt
        print(f"Sending goal:\n     {to_yaml(goal)}", flush=True)
        sent = client.send_goal_async(goal, on_feedback if args.feedback else None)
        executor.spin_until_future_complete(sent)
        goal_handle = sent.result()
        if goal_handle is None:
            raise KeyboardInterrupt
        if not goal_handle.accepted:
            print("Goal was rejected.")
            return 0
        try:
            print(f"Goal accepted with ID: {bytes(goal_handle.goal_id.uuid).hex()}\n", flush=True)
            result = goal_handle.get_result_async()
            executor.spin_until_future_complete(result)
            if not result.done():
                raise KeyboardInterrupt
        except KeyboardInterrupt:
            # as ros2 does: a goal left running when the command stops is canceled
            print("Canceling goal...", flush=True)
            goal_handle.cancel_goal()
            print("Goal canceled.")
            return 0
        response = result.result()
        print(f"Result:\n    {to_yaml(response.result)}")
        print(f"Goal finished with status: {_STATUS.get(response.status, 'UNKNOWN')}")
    return 0
