"""``launchkit topic pub``: publish a message, as ``ros2 topic pub`` does and says."""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros.message_data import build, mentions_now, parse_values
from launchkit.ros.message_text import short_repr
from launchkit.ros.msgs import get_message, message_type_name
from launchkit.ros_cli.common import CliUsageError, cli_node, normalize_topic
from launchkit.ros_cli.qos_options import profile_from_args

_WAIT_STEP = 0.1  # ros2 checks for subscriptions every 100 ms and says so every second


def pub(args: argparse.Namespace) -> int:
    """Publish ``args.values`` on ``args.topic_name`` at ``args.rate`` (``--once``/``-t N``)."""
    msg_class = get_message(args.message_type)
    type_name = message_type_name(msg_class)
    text = sys.stdin.read() if args.stdin else args.values
    data = parse_values(type_name, text)
    if not isinstance(data, dict):
        raise CliUsageError(
            "The passed value needs to be a dictionary in YAML format",
            expected=f"a mapping of {type_name} fields, e.g. '{{}}'",
        )
    times = 1 if args.once else args.times
    wanted = args.wait_matching_subscriptions
    if wanted is None:
        wanted = int(times != 0)
    if wanted == 0 and args.max_wait_time_secs is not None:
        raise CliUsageError(
            "--max-wait-time-secs option is only effective with "
            "--wait-matching-subscriptions, --once or --times"
        )
    # a mistake in the values shows before anything starts
    build(type_name, data, type_name, get_message("builtin_interfaces/msg/Time"))
    with cli_node(args, args.node_name) as node:
        publisher = node.create_publisher(
            msg_class, normalize_topic(args.topic_name), profile_from_args(args)
        )
        _wait_for_subscriptions(publisher, wanted, args.max_wait_time_secs)

        def now() -> Any:
            return node.get_clock().now().to_msg()

        changing = mentions_now(data)
        msg = build(type_name, data, type_name, now)
        print("publisher: beginning loop")
        period = 1.0 / args.rate
        count = 0
        next_time = time.monotonic()
        while node.context.ok():
            if changing and count:
                msg = build(type_name, data, type_name, now)
            count += 1
            if args.print_nth and count % args.print_nth == 0:
                print(f"publishing #{count}: {short_repr(msg)}\n", flush=True)
            publisher.publish(msg)
            if times and count >= times:
                break
            next_time += period
            time.sleep(max(0.0, next_time - time.monotonic()))
        # give the last messages time to reach the wire before the session closes
        time.sleep(args.keep_alive)
    return 0


def _wait_for_subscriptions(publisher: Any, wanted: int, max_wait: float | None) -> None:
    waited = 0.0
    steps = 0
    while publisher.get_subscription_count() < wanted:
        if steps % 10 == 0:
            print(f"Waiting for at least {wanted} matching subscription(s)...", flush=True)
        if max_wait is not None and waited >= max_wait:
            raise RuntimeLaunchError(
                f"Timed out waiting for subscribers: Expected {wanted} subcribers but only "
                f"got {publisher.get_subscription_count()} subscribers"
            )
        steps += 1
        time.sleep(_WAIT_STEP)
        waited += _WAIT_STEP
