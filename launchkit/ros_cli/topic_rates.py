"""``launchkit topic hz`` and ``topic bw``: a topic's rate and bandwidth, measured and printed
as ``ros2 topic hz`` and ``ros2 topic bw`` measure and print them."""

from __future__ import annotations

import argparse
import math
import threading
import time
from collections.abc import Callable
from typing import Any

from launchkit.ros.msgs import get_message
from launchkit.ros.qos import qos_profile_sensor_data
from launchkit.ros_cli.common import (
    cli_node,
    message_filter,
    normalize_topic,
    wait_for_topic_type,
)

_NS = 1_000_000_000


class RateMeter:
    """ros2 topic hz's arithmetic: the intervals between the last ``window`` messages (in
    nanoseconds of the clock given), reported at most once a second of message time."""

    def __init__(self, window: int, now: Callable[[], int]) -> None:
        self.window = window
        self.now = now
        self.lock = threading.Lock()
        self.first = -1
        self.last = 0
        self.last_reported = 0
        self.intervals: list[int] = []

    def on_message(self) -> None:
        """Count a message arriving now."""
        current = self.now()
        with self.lock:
            if self.first < 0 or self.first > current:  # the first message, or time went back
                self.first = self.last = current
                self.intervals = []
                return
            self.intervals.append(current - self.last)
            self.last = current
            del self.intervals[: -self.window]

    def report(self) -> str | None:
        """The lines to print now, or None (no new message, or less than a second since the
        last report)."""
        with self.lock:
            if not self.intervals:
                return None
            if self.last_reported == 0:
                self.last_reported = self.last
                return None
            if self.last < self.last_reported + _NS:
                return None
            self.last_reported = self.last
            n = len(self.intervals)
            mean = sum(self.intervals) / n
            rate = 1.0 / mean if mean > 0 else 0.0
            std = math.sqrt(sum((x - mean) ** 2 for x in self.intervals) / n)
            low, high = min(self.intervals), max(self.intervals)
        return (
            f"average rate: {rate * 1e9:.3f}\n"
            f"\tmin: {low * 1e-9:.3f}s max: {high * 1e-9:.3f}s std dev: {std * 1e-9:.5f}s "
            f"window: {n}"
        )


def hz(args: argparse.Namespace) -> int:
    """Print the rate of ``args.topic_name`` until Ctrl-C."""
    from launchkit.ros.executor import spin_once

    topic = normalize_topic(args.topic_name)
    keep = message_filter(args.filter_expr) if args.filter_expr else None
    with cli_node(args) as node:
        type_name, _ = wait_for_topic_type(node, topic, None)
        meter = RateMeter(args.window_size, _clock_ns(node, args.use_wtime))

        def on_message(msg: Any) -> None:
            if keep is None or keep(msg):
                meter.on_message()

        node.create_subscription(
            get_message(type_name), topic, on_message, qos_profile_sensor_data, raw=keep is None
        )
        while node.context.ok():
            spin_once(node, timeout_sec=0.5)
            report = meter.report()
            if report is not None:
                print(report, flush=True)
    return 0


def _clock_ns(node: Any, wall: bool) -> Callable[[], int]:
    if wall:
        return time.time_ns
    clock = node.get_clock()
    return lambda: int(clock.now().nanoseconds)


class BandwidthMeter:
    """ros2 topic bw's arithmetic: the sizes of the last ``window`` messages and when they came."""

    def __init__(self, window: int, now: Callable[[], int]) -> None:
        self.window = window
        self.now = now
        self.lock = threading.Lock()
        self.times: list[int] = []
        self.sizes: list[int] = []

    def on_message(self, data: bytes) -> None:
        """Count a serialized message arriving now."""
        with self.lock:
            self.times.append(self.now())
            self.sizes.append(len(data))
            del self.times[: -self.window], self.sizes[: -self.window]

    def report(self) -> str | None:
        """The lines to print now, or None before two messages came."""
        with self.lock:
            if len(self.times) < 2:
                return None
            elapsed = (self.now() - self.times[0]) / _NS
            if elapsed <= 0:
                self.times, self.sizes = [], []
                return None
            n, total = len(self.sizes), sum(self.sizes)
            low, high = min(self.sizes), max(self.sizes)
        per_second = total / elapsed
        shown = [_size(v, per_second) for v in (per_second, total / n, low, high)]
        return (
            f"{shown[0]}/s from {n} messages\n"
            f"\tMessage size mean: {shown[1]} min: {shown[2]} max: {shown[3]}"
        )


def _size(value: float, scale: float) -> str:
    """``value`` bytes in the unit ``scale`` (the bandwidth) calls for, as ros2 topic bw does."""
    if scale < 1000:
        return f"{value:.0f} B"
    if scale < 1_000_000:
        return f"{value / 1000:.2f} KB"
    return f"{value / 1000 / 1000:.2f} MB"


def bw(args: argparse.Namespace) -> int:
    """Print the bandwidth of ``args.topic_name`` every second until Ctrl-C."""
    from launchkit.ros.executor import spin_once

    topic = normalize_topic(args.topic_name)
    with cli_node(args) as node:
        type_name, _ = wait_for_topic_type(node, topic, None)
        meter = BandwidthMeter(args.window, _clock_ns(node, False))
        node.create_subscription(
            get_message(type_name), topic, meter.on_message, qos_profile_sensor_data, raw=True
        )
        print(f"Subscribed to [{topic}]", flush=True)
        next_report = time.monotonic() + 1.0
        while node.context.ok():
            spin_once(node, timeout_sec=max(0.0, next_report - time.monotonic()))
            if time.monotonic() >= next_report:
                next_report += 1.0
                report = meter.report()
                if report is not None:
                    print(report, flush=True)
    return 0
