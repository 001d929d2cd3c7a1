"""Bridge benchmark: what ``launchkit bridge`` adds between launchkit nodes and real rclpy nodes.

Run by hand: ``python bench/bridge.py`` (needs the ``ros2`` extra). It hosts a router on a free
loopback port, runs ``launchkit bridge`` on a private ROS domain with DDS discovery on loopback,
and, with every publisher and subscriber its own process, measures:
  * one-way latency p50/p99 of 100 B (500 Hz) and 1 MB (20 Hz) messages, launchkit -> DDS and
    DDS -> launchkit through the bridge, and the native paths launchkit -> launchkit and
    rclpy -> rclpy in the same run; "added" is the bridged p50 minus the destination side's
    native p50 (what a subscriber sees on top of a publisher of its own kind);
  * throughput of 100 B messages, each way (publisher flat out for 3 s; received per second);
  * how long a new topic takes to reach the other side: from the publisher's creation to the
    subscriber's first message, with the subscriber already waiting, each way and natively (a
    DDS publisher is created once its process's participant has discovered the others, 3
    nodes: participant discovery is Fast DDS's own 0.25-1.8 s, not the bridge's).
Payloads are std_msgs/UInt8MultiArray CDR carrying the sender's CLOCK_MONOTONIC; both sides
read them raw, nothing is decoded. The last line is ``bridge: added p50 A us (100 B, launchkit
-> DDS), throughput N msg/s (DDS -> launchkit), new topic T ms``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import random
import statistics
import struct
import subprocess
import sys
import time
from datetime import datetime, timezone
from typing import Any

TYPE = "std_msgs/msg/UInt8MultiArray"
# UInt8MultiArray with no dims: header, dim count 0, data_offset 0, data length, then data
PREFIX = struct.Struct("<4sIII")
STAMP = struct.Struct("<qI")  # sender's monotonic ns, sequence number
WARMUP = {100: 100, 1_000_000: 5}  # messages not counted, by size
ENV = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "RCUTILS_LOGGING_USE_STDOUT": "1"}


def payload(size: int, seq: int) -> bytes:
    """A UInt8MultiArray of ``size`` data bytes starting with the send time."""
    data = STAMP.pack(time.monotonic_ns(), seq) + bytes(max(0, size - STAMP.size))
    return PREFIX.pack(b"\x00\x01\x00\x00", 0, 0, len(data)) + data


def stamp_of(data: bytes) -> tuple[int, int]:
    """(send time ns, sequence) of a payload (Fast DDS may have padded its end)."""
    sent, seq = STAMP.unpack_from(data, PREFIX.size)
    return int(sent), int(seq)


# --- one side of a measurement, in its own process -------------------------------------------


class Side:
    """Publishes and subscribes raw CDR bytes on one side: launchkit (``lk``) or rclpy (``dds``)."""

    def __init__(self, kind: str, name: str = "") -> None:
        self.kind = kind
        name = name or f"bench_{os.getpid()}"
        if kind == "lk":
            import launchkit.ros as ros
            from launchkit.ros.msgs import get_message

            ros.init([])
            self.ros = ros
            self.node = ros.Node(name)
            self.cls = get_message(TYPE)
        else:
            import rclpy
            from rclpy.executors import SingleThreadedExecutor
            from std_msgs.msg import UInt8MultiArray

            rclpy.init()
            self.ros = rclpy
            self.node = rclpy.create_node(name)
            self.executor = SingleThreadedExecutor()
            self.executor.add_node(self.node)
            self.cls = UInt8MultiArray

    def publisher(self, topic: str) -> Any:
        """A reliable depth-10 publisher."""
        return self.node.create_publisher(self.cls, topic, 10)

    def subscribe(self, topic: str, on_data: Any) -> None:
        """Call ``on_data(bytes)`` for every message."""
        self.node.create_subscription(self.cls, topic, on_data, 10, raw=True)

    def spin_once(self, timeout: float) -> None:
        """Run callbacks for up to ``timeout`` seconds."""
        if self.kind == "lk":
            self.ros.spin_once(self.node, timeout_sec=timeout)
        else:
            self.executor.spin_once(timeout_sec=timeout)

    def close(self) -> None:
        """Shut down."""
        self.ros.shutdown()


def _idle(side: Side, seconds: float) -> None:
    # an rclpy publisher spins (discovery needs it); launchkit's needs nothing
    if side.kind == "dds":
        side.spin_once(seconds)
    else:
        time.sleep(seconds)


def role_pub(kind: str, topic: str, size: int, rate: float, seconds: float) -> None:
    """Publish on ``topic`` at ``rate`` (0: flat out) for ``seconds``; report what was sent."""
    side = Side(kind)
    pub = side.publisher(topic)
    deadline = time.monotonic() + 30
    while not pub.get_subscription_count() and time.monotonic() < deadline:
        _idle(side, 0.01)  # matched first: discovery is measured apart (new topic)
    print("READY", flush=True)
    sent, start = 0, time.monotonic()
    period = 1.0 / rate if rate else 0.0
    while time.monotonic() - start < seconds:
        pub.publish(payload(size, sent))
        sent += 1
        if period:
            next_at = start + sent * period
            while time.monotonic() < next_at:
                _idle(side, 0.0002)
    print(json.dumps({"sent": sent}), flush=True)
    side.close()


def role_sub(kind: str, topic: str, seconds: float, warmup: int) -> None:
    """Receive on ``topic`` for ``seconds``; report one-way latencies and the count."""
    side = Side(kind)
    latencies: list[int] = []
    count = [0, 0.0, 0.0]  # received, first and last receive time

    def on_data(data: bytes) -> None:
        now = time.monotonic_ns()
        if len(data) < PREFIX.size + STAMP.size:
            return
        sent, seq = stamp_of(data)
        if count[0] == 0:
            count[1] = now / 1e9
        count[0] += 1
        count[2] = now / 1e9
        if seq >= warmup:
            latencies.append(now - sent)

    side.subscribe(topic, on_data)
    print("READY", flush=True)
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        side.spin_once(0.05)
    span = count[2] - count[1]
    rate = count[0] / span if span > 0 else 0.0
    print(json.dumps({"latencies": latencies, "received": count[0], "rate": rate}), flush=True)
    side.close()


def role_first(kind: str, topic: str, timeout: float) -> None:
    """Wait for the first message on ``topic``; report its one-way time (publisher creation
    time travels in the payload's stamp, sequence 0)."""
    side = Side(kind, "first" + topic.replace("/", "_"))
    got: list[int] = []

    def on_data(data: bytes) -> None:
        if not got and len(data) >= PREFIX.size + STAMP.size:
            got.append(time.monotonic_ns() - stamp_of(data)[0])

    side.subscribe(topic, on_data)
    print("READY", flush=True)
    end = time.monotonic() + timeout
    while not got and time.monotonic() < end:
        side.spin_once(0.01)
    print(json.dumps({"first_ns": got[0] if got else None}), flush=True)
    side.close()


def role_new_pub(kind: str, topic: str, seconds: float, peer: str) -> None:
    """Create a publisher and publish at 1 kHz, every stamp the creation time (seq 0)."""
    side = Side(kind)
    if kind == "dds":  # an established DDS node: its participant already knows the others
        deadline = time.monotonic() + 30
        while peer not in side.node.get_node_names() and time.monotonic() < deadline:
            _idle(side, 0.01)
    print("READY", flush=True)
    created = time.monotonic_ns()
    pub = side.publisher(topic)
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        data = bytearray(payload(100, 0))
        STAMP.pack_into(data, PREFIX.size, created, 0)
        pub.publish(bytes(data))
        _idle(side, 0.001)
    print(json.dumps({}), flush=True)
    side.close()


# --- the driver ------------------------------------------------------------------------------


def _child(env: dict[str, str], *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, __file__, "--role", *args],
        stdout=subprocess.PIPE,
        text=True,
        env=env,
    )


def _wait_line(proc: subprocess.Popen[str], text: str, timeout: float = 60.0) -> str:
    assert proc.stdout is not None
    deadline = time.monotonic() + timeout
    for line in proc.stdout:
        if text in line:
            return line
        if time.monotonic() > deadline:
            break
    raise RuntimeError(f"child never printed {text!r}")


def _result(proc: subprocess.Popen[str]) -> dict[str, Any]:
    assert proc.stdout is not None
    out, _ = proc.communicate(timeout=120)
    for line in reversed(out.splitlines()):
        if line.startswith("{"):
            return dict(json.loads(line))
    raise RuntimeError("child printed no result")


def _pct(values: list[int], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] / 1000.0 if ordered else 0.0


def measure(env: dict[str, str], src: str, dst: str, size: int, rate: float, secs: float) -> Any:
    """(p50 µs, p99 µs, received, received per second) from a ``src`` publisher to a ``dst``
    subscriber (through the bridge when the kinds differ)."""
    topic = f"/bench_{src}_{dst}_{size}_{random.randrange(1 << 30)}"
    sub = _child(env, "sub", dst, topic, str(secs + 8.0), str(WARMUP.get(size, 100)))
    _wait_line(sub, "READY")
    time.sleep(1.5)  # discovery of the bridge's route and DDS matching (not measured)
    pub = _child(env, "pub", src, topic, str(size), str(rate), str(secs))
    _result(pub)
    result = _result(sub)
    lat = result["latencies"]
    return _pct(lat, 0.5), _pct(lat, 0.99), result["received"], result["rate"]


def new_topic(env: dict[str, str], src: str, dst: str) -> float | None:
    """ms from a publisher's creation to the first message at an already waiting subscriber."""
    topic = f"/bench_new_{random.randrange(1 << 30)}"
    first = _child(env, "first", dst, topic, "20")
    _wait_line(first, "READY")
    time.sleep(1.0)  # the subscriber's own discovery is not what is measured
    peer = "first" + topic.replace("/", "_") if dst == "dds" else "launchkit_bridge"
    pub = _child(env, "new_pub", src, topic, "6", peer)
    result = _result(first)
    _result(pub)
    return None if result["first_ns"] is None else result["first_ns"] / 1e6


def main() -> int:
    """Run every measurement and print the table lines."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--role", nargs="+")
    parser.add_argument("--quick", action="store_true", help="shorter runs")
    args = parser.parse_args()
    if args.role:
        role, kind, *rest = args.role
        functions = {"pub": role_pub, "sub": role_sub, "first": role_first, "new_pub": role_new_pub}
        conv = {"pub": (str, int, float, float), "sub": (str, float, int), "first": (str, float),
                "new_pub": (str, float, str)}[role]  # fmt: skip
        functions[role](kind, *[c(v) for c, v in zip(conv, rest, strict=True)])  # type: ignore[operator]
        return 0

    from launchkit.ros.router import start_router
    from launchkit.testing._isolation import free_loopback_port, router_endpoint

    endpoint = router_endpoint(free_loopback_port())
    router = start_router(endpoint)
    domain = str(150 + os.getpid() % 80)
    env = {**os.environ, **ENV, "LAUNCHKIT_ROUTER": endpoint, "ROS_DOMAIN_ID": domain}
    bridge = subprocess.Popen(
        [sys.executable, "-m", "launchkit", "bridge", "--router", endpoint],
        env=env,
        stdout=subprocess.DEVNULL,
    )
    secs = 2.0 if args.quick else 4.0
    when = f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC"
    print(f"# {when}, {platform.platform()}, {os.cpu_count()} cores, Python "
          f"{platform.python_version()}, ROS_DOMAIN_ID {domain}")  # fmt: skip
    results: dict[str, Any] = {}
    try:
        time.sleep(2.0)  # the bridge's start (rclpy import, DDS participant)
        for size, rate, label in ((100, 500.0, "100 B"), (1_000_000, 20.0, "1 MB")):
            for src, dst in (("lk", "lk"), ("dds", "dds"), ("lk", "dds"), ("dds", "lk")):
                p50, p99, n, _ = measure(env, src, dst, size, rate, secs)
                results[(label, src, dst)] = p50
                print(f"latency {label:6} {src:>3} -> {dst:<3} p50 {p50:9.1f} us  "
                      f"p99 {p99:9.1f} us  (n={n})")  # fmt: skip
            for src, dst in (("lk", "dds"), ("dds", "lk")):
                added = results[(label, src, dst)] - results[(label, dst, dst)]
                print(f"added  {label:6} {src:>3} -> {dst:<3} p50 {added:9.1f} us "
                      f"(bridged - native {dst})")  # fmt: skip
        for src, dst in (("lk", "lk"), ("dds", "dds"), ("lk", "dds"), ("dds", "lk")):
            *_, n, rate = measure(env, src, dst, 100, 0.0, 3.0)
            results[("rate", src, dst)] = rate
            print(f"throughput 100 B {src:>3} -> {dst:<3} {rate:9.0f} msg/s received (n={n})")
        for src, dst in (("lk", "lk"), ("dds", "dds"), ("lk", "dds"), ("dds", "lk")):
            times = [new_topic(env, src, dst) for _ in range(3 if args.quick else 5)]
            shown = ", ".join("lost" if t is None else f"{t:.0f}" for t in times)
            valid = [t for t in times if t is not None]
            results[("new", src, dst)] = statistics.median(valid) if valid else float("nan")
            print(f"new topic {src:>3} -> {dst:<3} first message after {shown} ms")
    finally:
        bridge.terminate()
        bridge.wait(15)
        router.close()
    added = results[("100 B", "lk", "dds")] - results[("100 B", "dds", "dds")]
    print(
        f"bridge: added p50 {added:.0f} us (100 B, launchkit -> DDS), throughput "
        f"{results[('rate', 'dds', 'lk')]:.0f} msg/s (DDS -> launchkit), new topic "
        f"{results[('new', 'lk', 'dds')]:.0f} ms"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
