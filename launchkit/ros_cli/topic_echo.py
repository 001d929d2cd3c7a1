"""``launchkit topic echo``: a topic's messages printed as ``ros2 topic echo`` prints them."""

from __future__ import annotations

import argparse
import sys
import threading
import time
from collections.abc import Callable
from typing import Any

import yaml

from launchkit.ros.message_data import fields_of
from launchkit.ros.message_text import is_message, to_csv, to_yaml, value_text
from launchkit.ros.msgs import get_message, message_type_name, normalize_type_name
from launchkit.ros_cli.common import (
    CliUsageError,
    cli_node,
    graph_tokens,
    message_filter,
    normalize_topic,
    wait_for_topic_type,
)
from launchkit.ros_cli.qos_options import subscription_profile


class _Printer:
    """Prints each message (or the field ``--field`` selects) in the form the options ask."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.truncate = None if args.full_length else args.truncate_length
        self.path = _field_path(args.field)
        self.keep: Callable[[Any], bool] | None = (
            message_filter(args.filter_expr) if args.filter_expr else None
        )

    def __call__(self, msg: Any, info: dict[str, Any]) -> bool:
        """Print ``msg``; False if the filter left it out."""
        value, desc = self._select(msg)
        if self.keep is not None and not self.keep(value):
            return False
        if isinstance(value, bytes) and self.args.raw:
            self._info(info, raw=True)
            sys.stdout.write(f"{value!r}\n---\n")
        elif not is_message(value):
            sys.stdout.write(f"{value_text(value, desc)}\n---\n")
        elif self.args.csv:
            text = to_csv(value, self.truncate, no_arr=self.args.no_arr, no_str=self.args.no_str)
            if self.args.include_message_info:
                text = ",".join(str(v) for v in _rclpy_info(info).values()) + "," + text
            sys.stdout.write(text + "\n")
        else:
            self._info(info, raw=False)
            text = to_yaml(
                value,
                self.truncate,
                no_arr=self.args.no_arr,
                no_str=self.args.no_str,
                flow_style=self.args.flow_style,
            )
            sys.stdout.write(text + "---\n")
        sys.stdout.flush()
        return True

    def _select(self, msg: Any) -> tuple[Any, Any]:
        """The message, or its field ``--field`` names, and that field's description."""
        value, desc = msg, None
        for name in self.path:
            fields = dict(fields_of(message_type_name(value))) if is_message(value) else {}
            if name not in fields:
                raise CliUsageError(
                    f"invalid field '{'.'.join(self.path)}': "
                    f"{type(value).__name__} has no field {name!r}",
                    expected="one of: " + ", ".join(fields) if fields else "a message field",
                )
            value, desc = getattr(value, name), fields[name]
        return value, desc

    def _info(self, info: dict[str, Any], raw: bool) -> None:
        if not self.args.include_message_info:
            return
        if raw:
            sys.stdout.write(f"---Got new message, message info:---\n{_rclpy_info(info)}\n")
            sys.stdout.write("---Message data:---\n")
        else:
            sys.stdout.write(yaml.safe_dump(_rclpy_info(info)) + "---\n")


def _rclpy_info(info: dict[str, Any]) -> dict[str, Any]:
    """The message info rclpy hands a callback (launchkit adds the publisher's GID)."""
    return {key: value for key, value in info.items() if key != "publisher_gid"}


def _field_path(text: str | None) -> list[str]:
    if text is None:
        return []
    path = [part for part in text.split(".") if part]
    if not path:
        raise CliUsageError(f"invalid field value {text!r}", expected="e.g. pose.position")
    return path


def echo(args: argparse.Namespace) -> int:
    """Print the messages of ``args.topic_name`` until Ctrl-C, ``--once`` or ``--timeout``."""
    from launchkit.ros.executor import spin_once

    topic = normalize_topic(args.topic_name)
    msg_class = get_message(args.message_type) if args.message_type else None
    printer = _Printer(args)
    started = time.monotonic()
    with cli_node(args) as node:
        if args.message_type:
            type_name, tokens = normalize_type_name(args.message_type), graph_tokens(node)
        else:
            type_name, tokens = wait_for_topic_type(node, topic, args.timeout)
        msg_class = msg_class or get_message(type_name)
        publishers = [t for t in tokens if t.kind == "MP" and t.topic == topic]
        qos = subscription_profile(args, publishers)
        done = threading.Event()

        def show(msg: Any, info: dict[str, Any]) -> None:
            if done.is_set():
                return
            if printer(msg, info) and args.once:
                done.set()

        node.create_subscription(msg_class, topic, show, qos, raw=args.raw)
        while not done.is_set() and node.context.ok():
            if args.timeout is not None and time.monotonic() - started >= args.timeout:
                break
            spin_once(node, timeout_sec=0.1)
    return 0
