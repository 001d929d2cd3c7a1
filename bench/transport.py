"""Transport benchmark: launchkit.ros nodes against raw zenoh-python, in separate processes.

Run by hand: ``python bench/transport.py``. It hosts a router on a free loopback port and,
for launchkit.ros and raw zenoh in turn, measures
  * one-way latency p50/p99 of 100 B messages (1 kHz) and 100 KB messages (100 Hz),
  * throughput of 100 B messages (publisher flat out; messages the subscriber's callback got
    per second while the publisher ran, with received/sent, what came after it stopped and
    the subscription's depth: 10, then KEEP_ALL),
  * time to the first message: from the subscriber's process start, and from its
    ``init()``/``zenoh.open()``, while a publisher already sends at 1 kHz.
Latency is the receiver's CLOCK_MONOTONIC minus the sender's (one clock, shared by processes).
``--kind hop`` (a child role, and a third latency line of the full run) is raw zenoh whose
callback only hands the bytes to the main thread through the executor's ``WorkQueue``: what
rclpy's threading (callbacks in the spinning thread) costs with nothing else of the ROS layer.
``--throughput-rounds N --tree LABEL=DIR ...`` only measures throughput: raw zenoh and each
tree (``git archive`` exports, run by ``PYTHONPATH``) alternating, N rounds.
The last line is ``transport: p50 ratio R (launchkit/raw zenoh), throughput N msg/s
(KEEP_ALL K), first message T ms`` (R for 100 B; N (depth 10), K and T for launchkit.ros; T
from init).

``python bench/transport.py --steps`` instead times each step of the per-message path in one
process (median of many calls, microseconds): building the message, serializing it, the
attachment, Zenoh's put, the receiver's copy out of Zenoh, decoding, and the subscription's
queue-and-dispatch to the callback; for a 100 B byte array, a 100 KB one and an 800x800 rgb8
Image. Serialize and decode are also timed the way launchkit did them before its per-type
codec (rosbags' Typestore.serialize_cdr + bytes(), deserialize_cdr on bytes), for comparison.
First, the executor's hand-off alone: from ``put`` in one thread to a waiting spinner thread
holding the item (median delay), with the executor's ``WorkQueue`` and with ``queue.Queue``.
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import platform
import socket
import statistics
import struct
import subprocess
import sys
import threading
import time
from datetime import datetime, timezone
from typing import Any

HEADER = struct.Struct("<qI")  # sender's monotonic ns, sequence number
WARMUP = 200


def _payload(size: int, seq: int) -> bytes:
    head = HEADER.pack(time.monotonic_ns(), seq)
    return head + bytes(max(0, size - len(head)))


# --- child roles ----------------------------------------------------------------------------


class _Transport:
    """One side's way to publish and subscribe raw bytes (launchkit.ros or raw zenoh)."""

    def __init__(self, kind: str, depth: int = 10) -> None:
        self.kind = kind
        self.depth = depth  # the launchkit.ros subscription's KEEP_LAST depth; 0: KEEP_ALL
        self.hop: Any = None
        if kind == "hop":  # raw zenoh, its callback handing each sample to the main thread
            from launchkit.ros.executor import WorkQueue

            self.hop = WorkQueue()
            kind = self.kind = "raw"
        if kind == "raw":
            import zenoh

            from launchkit.ros.session import peer_config, wait_for_router

            self.session = zenoh.open(peer_config())
            wait_for_router(self.session, 5.0)
        else:
            from launchkit.ros.msgs.std_msgs.msg import UInt8MultiArray

            import launchkit.ros as ros

            ros.init([])
            self.ros = ros
            self.msg_type = UInt8MultiArray
            self.node = ros.Node(f"bench_{os.getpid()}")

    def publisher(self) -> Any:
        if self.kind == "raw":
            pub = self.session.declare_publisher("bench/data")
            return lambda data: pub.put(data)
        pub = self.node.create_publisher(self.msg_type, "bench/data", 10)
        msg_type = self.msg_type
        return lambda data: pub.publish(msg_type(data=data))

    def subscribe(self, on_data: Any) -> None:
        if self.kind == "raw" and self.hop is not None:
            put = self.hop.put
            self.session.declare_subscriber(
                "bench/data", lambda s: put((on_data, (s.payload.to_bytes(),)))
            )
        elif self.kind == "raw":
            self.session.declare_subscriber("bench/data", lambda s: on_data(s.payload.to_bytes()))
        else:
            from launchkit.ros import HistoryPolicy, QoSProfile

            qos = (
                QoSProfile(depth=self.depth)
                if self.depth
                else QoSProfile(depth=10, history=HistoryPolicy.KEEP_ALL)
            )
            self.node.create_subscription(
                self.msg_type, "bench/data", lambda m: on_data(m.data[:12].tobytes()), qos
            )

    def run_for(self, seconds: float, until: Any = None) -> None:
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline and not (until and until()):
            if self.hop is not None:
                item = self.hop.get(0.01)
                if item is not None:
                    item[0](*item[1])
            elif self.kind == "raw":
                time.sleep(0.01)
            else:
                self.ros.spin_once(self.node, timeout_sec=0.01)

    def ok(self) -> bool:
        return self.kind == "raw" or bool(self.ros.ok())

    def close(self) -> None:
        if self.kind == "raw":
            self.session.close()
        else:
            self.ros.shutdown()


def role_pub(kind: str, size: int, rate: float, count: int, seconds: float) -> None:
    try:
        _publish(kind, size, rate, count, seconds)
    except KeyboardInterrupt:  # raw zenoh's side, stopped by the parent
        pass


def _publish(kind: str, size: int, rate: float, count: int, seconds: float) -> None:
    side = _Transport(kind)
    put = side.publisher()
    print("ready", flush=True)
    period = 1.0 / rate if rate else 0.0
    next_t = time.monotonic()
    seq = 0
    end = time.monotonic() + seconds if seconds else None
    first_ns = time.monotonic_ns()
    while side.ok() and ((count and seq < count) or (end and time.monotonic() < end)):
        put(_payload(size, seq))
        seq += 1
        if period:
            next_t += period
            delay = next_t - time.monotonic()
            if delay > 0:
                time.sleep(delay)
    last_ns = time.monotonic_ns()
    side.close()
    try:
        print(json.dumps({"sent": seq, "first_ns": first_ns, "last_ns": last_ns}), flush=True)
    except BrokenPipeError:  # the parent stopped reading (first-message runs)
        pass


def role_sub(kind: str, expect: int, seconds: float, first_only: bool, depth: int = 10) -> None:
    started = time.monotonic_ns()
    side = _Transport(kind, depth)
    opened = time.monotonic_ns()
    latencies: list[int] = []
    stamps: list[int] = []
    seqs: list[int] = []

    def on_data(data: bytes) -> None:
        now = time.monotonic_ns()
        sent, seq = HEADER.unpack_from(data)
        stamps.append(now)
        seqs.append(seq)
        if seq >= WARMUP:
            latencies.append(now - sent)

    side.subscribe(on_data)
    print("ready", flush=True)
    if first_only:
        side.run_for(seconds, until=lambda: bool(stamps))
    elif expect:
        side.run_for(seconds, until=lambda: len(latencies) >= expect)
    else:  # throughput: until one second of silence after the first message
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            before = len(stamps)
            side.run_for(1.0)
            if stamps and len(stamps) == before:
                break
    side.close()
    span = (stamps[-1] - stamps[0]) / 1e9 if len(stamps) > 1 else 0.0
    print(
        json.dumps(
            {
                "latencies_ns": latencies,
                "received": len(stamps),
                "rate": (len(stamps) - 1) / span if span else 0.0,
                "last_ns": stamps[-1] if stamps else None,
                # arrival times in ms after the first (the parent counts those while the
                # publisher ran) and whether every delivered message came in order
                "stamps_ms": [(t - stamps[0]) // 1_000_000 for t in stamps] if expect == 0 else [],
                "ordered": all(a < b for a, b in itertools.pairwise(seqs)),
                "first_ns": stamps[0] if stamps else None,
                "started_ns": started,
                "opened_ns": opened,
            }
        ),
        flush=True,
    )


# --- orchestration --------------------------------------------------------------------------


def _child(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, __file__, *args], stdout=subprocess.PIPE, text=True, env=os.environ.copy()
    )


def _wait_line(proc: subprocess.Popen[str], text: str) -> None:
    assert proc.stdout is not None
    line = proc.stdout.readline()
    if text not in line:
        raise RuntimeError(f"child said {line!r}, expected {text!r}")


def _result(proc: subprocess.Popen[str], timeout: float = 60.0) -> dict[str, Any]:
    out, _ = proc.communicate(timeout=timeout)
    return dict(json.loads(out.strip().splitlines()[-1]))


def _pair(kind: str, sub_args: list[str], pub_args: list[str]) -> dict[str, Any]:
    result, _ = _pair_both(kind, sub_args, pub_args)
    return result


def _pair_both(
    kind: str, sub_args: list[str], pub_args: list[str]
) -> tuple[dict[str, Any], dict[str, Any]]:
    """Run a subscriber and a publisher; what each reported (the subscriber's, the
    publisher's)."""
    sub = _child("--role", "sub", "--kind", kind, *sub_args)
    _wait_line(sub, "ready")
    pub = _child("--role", "pub", "--kind", kind, *pub_args)
    _wait_line(pub, "ready")
    result = _result(sub)
    sent = _result(pub)
    return result, sent


def _pct(values: list[int], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] / 1000.0


def latency(kind: str, size: int, rate: float, count: int) -> tuple[float, float, int]:
    total = count + WARMUP
    result = _pair(
        kind,
        ["--expect", str(count), "--seconds", str(total / rate + 10)],
        ["--size", str(size), "--rate", str(rate), "--count", str(total)],
    )
    lat = result["latencies_ns"]
    return _pct(lat, 0.5), _pct(lat, 0.99), len(lat)


def throughput(kind: str, seconds: float, depth: int = 10) -> dict[str, Any]:
    """100 B messages flat out for ``seconds``: ``rate`` is what the subscriber delivered per
    second while the publisher ran (its callbacks between the publisher's first and last put),
    ``received``/``sent`` all it delivered of all that was sent, ``after`` how many of those
    came after the publisher stopped (a backlog drained) and ``span_rate`` the old figure:
    deliveries over the span from the first to the last delivery, drain included. ``depth``:
    the launchkit.ros subscription's KEEP_LAST depth (0: KEEP_ALL)."""
    result, pub = _pair_both(
        kind,
        ["--seconds", str(seconds + 30), "--depth", str(depth)],
        ["--size", "100", "--rate", "0", "--seconds", str(seconds)],
    )
    first = result["first_ns"]
    pub_end_ms = (pub["last_ns"] - first) / 1e6
    during = sum(1 for t in result["stamps_ms"] if t <= pub_end_ms)
    window = (pub["last_ns"] - max(first, pub["first_ns"])) / 1e9
    return {
        "rate": during / window if window > 0 else 0.0,
        "received": result["received"],
        "sent": pub["sent"],
        "after": result["received"] - during,
        "drain_s": max(0.0, (result["last_ns"] - pub["last_ns"]) / 1e9),
        "span_rate": float(result["rate"]),
        "ordered": result["ordered"],
        "depth": depth,
    }


def _throughput_line(label: str, r: dict[str, Any]) -> str:
    depth = "" if r.get("depth") is None else f", depth {r['depth'] or 'KEEP_ALL'}"
    return (
        f"{label:14s} 100 B  throughput {r['rate']:10.0f} msg/s while publishing "
        f"(received {r['received']} of {r['sent']} sent = {r['received'] / max(1, r['sent']):.2f}, "
        f"{r['after']} after the publisher stopped, drained in {r['drain_s']:.2f} s; "
        f"first-to-last rate {r['span_rate']:.0f}{depth}; in order: {r['ordered']})"
    )


def first_message(kind: str, runs: int) -> tuple[list[float], list[float]]:
    pub = _child(
        "--role", "pub", "--kind", kind, "--size", "100", "--rate", "1000", "--seconds", "600"
    )
    _wait_line(pub, "ready")
    from_start, from_open = [], []
    try:
        for _ in range(runs):
            t0 = time.monotonic_ns()
            sub = _child("--role", "sub", "--kind", kind, "--first", "--seconds", "10")
            result = _result(sub)
            if result["first_ns"] is None:
                raise RuntimeError("the subscriber got no message in 10 s")
            from_start.append((result["first_ns"] - t0) / 1e6)
            from_open.append((result["first_ns"] - result["opened_ns"]) / 1e6)
    finally:
        pub.send_signal(2)
        try:
            pub.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            pub.kill()
            pub.communicate()
    return from_start, from_open


def _per_call_us(action: Any, budget: float = 0.3) -> float:
    """Median microseconds of ``action()`` over batches filling about ``budget`` seconds."""
    action()
    start = time.perf_counter()
    action()
    once = max(time.perf_counter() - start, 1e-7)
    batch = max(1, int(0.01 / once))
    samples = []
    deadline = time.perf_counter() + budget
    while time.perf_counter() < deadline or len(samples) < 5:
        start = time.perf_counter()
        for _ in range(batch):
            action()
        samples.append((time.perf_counter() - start) / batch)
    return statistics.median(samples) * 1e6


class _Sample:
    """What a subscription reads of a Zenoh sample: payload and attachment (as ZBytes)."""

    def __init__(self, payload: Any, attachment: Any) -> None:
        self.payload, self.attachment = payload, attachment


def _case_steps(ros: Any, node: Any, msg_type: Any, build: Any) -> dict[str, float]:
    """Each step's microseconds for messages made by ``build()``."""
    import zenoh

    from launchkit.ros.keyexpr import decode_attachment, encode_attachment
    from launchkit.ros.msgs import codec

    name = msg_type._TYPE_NAME
    msg = build()
    coder = codec(name)
    data = coder.serialize(msg)
    payload = bytes(data)
    gid = bytes(16)
    attachment = encode_attachment(1, time.time_ns(), gid)
    publisher = node.context.session.declare_publisher(f"bench/steps/{len(data)}")
    sub = node.create_subscription(msg_type, f"bench/steps_{len(data)}", lambda _m: None, 10)
    sample = _Sample(zenoh.ZBytes(payload), zenoh.ZBytes(attachment))

    def dispatch() -> None:
        sub._on_sample(sample)
        ros.spin_once(node, timeout_sec=0)

    rows = {
        "build message": _per_call_us(build),
        "serialize": _per_call_us(lambda: coder.serialize(msg)),
        "attachment": _per_call_us(lambda: encode_attachment(2, time.time_ns(), gid)),
        "put (no remote subscriber)": _per_call_us(
            lambda: publisher.put(data, attachment=attachment)
        ),
        "receive: copy out of Zenoh": _per_call_us(lambda: sample.payload.to_bytes()),
        "decode": _per_call_us(lambda: coder.deserialize(payload)),
        "decode attachment (2-argument callbacks)": _per_call_us(
            lambda: decode_attachment(attachment)
        ),
        "queue + dispatch + decode + callback": _per_call_us(dispatch),
    }
    publisher.undeclare()
    node.destroy_subscription(sub)
    return rows


def _hop_us(make_queue: Any, count: int = 2000) -> float:
    """Median microseconds from ``put`` in one thread to ``get`` returning the item in a
    thread that was waiting for it (the executor's hand-off), one item per 0.5 ms."""
    work = make_queue()
    delays: list[int] = []

    def spinner() -> None:
        while len(delays) < count:
            item = work.get(0.5)
            if item is not None:
                delays.append(time.perf_counter_ns() - item[1][0])

    thread = threading.Thread(target=spinner, daemon=True)
    thread.start()
    while thread.is_alive():
        time.sleep(0.0005)
        work.put((None, (time.perf_counter_ns(),)))
    return statistics.median(delays) / 1000


class _QueueHandOff:
    """The executor's hand-off before this change: ``queue.Queue`` (a Condition's wait)."""

    def __init__(self) -> None:
        import queue

        self._queue: Any = queue.Queue()
        self.put = self._queue.put

    def get(self, timeout: float) -> Any:
        import queue

        try:
            return self._queue.get(timeout=timeout)
        except queue.Empty:
            return None


def steps() -> None:
    """Print the cost of each step of the per-message path (see the module's docstring)."""

    import launchkit.ros as ros
    from launchkit.ros.msgs import get_message

    ros.init([])
    node = ros.Node(f"bench_steps_{os.getpid()}")
    array_type = get_message("std_msgs/msg/UInt8MultiArray")
    image_type = get_message("sensor_msgs/msg/Image")
    pixels = bytes(800 * 800 * 3)
    cases = [
        ("100 B UInt8MultiArray", array_type, lambda: array_type(data=bytes(100))),
        ("100 KB UInt8MultiArray", array_type, lambda: array_type(data=bytes(100_000))),
        (
            "800x800 rgb8 Image",
            image_type,
            lambda: image_type(height=800, width=800, encoding="rgb8", step=2400, data=pixels),
        ),
    ]
    print(f"# per-message steps, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, microseconds")
    from launchkit.ros.executor import WorkQueue

    for label, make in (
        ("hand-off to a waiting spinner (WorkQueue)", WorkQueue),
        ("  before: queue.Queue", _QueueHandOff),
    ):
        print(f"{'any message':24s} {label:44s} {_hop_us(make):10.1f}")
    for label, msg_type, build in cases:
        for step, value in _case_steps(ros, node, msg_type, build).items():
            print(f"{label:24s} {step:44s} {value:10.1f}")
    ros.shutdown()


def throughput_rounds(rounds: int, trees: list[str], depth: int) -> None:
    """Throughput of raw zenoh and of each tree (``LABEL=DIR``, run by ``PYTHONPATH``; none:
    this one), at ``depth`` and KEEP_ALL, alternating, ``rounds`` times."""
    print(
        f"# throughput rounds, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, "
        f"load {os.getloadavg()[0]:.1f}"
    )
    pairs = [tree.split("=", 1) for tree in trees] or [["this tree", ""]]
    base = os.environ.get("PYTHONPATH")
    for index in range(rounds):
        raw = throughput("raw", 3.0)
        raw["depth"] = None
        print(f"round {index + 1}, load {os.getloadavg()[0]:.1f}")
        print(_throughput_line("raw zenoh", raw))
        for label, directory in pairs:
            if directory:
                os.environ["PYTHONPATH"] = directory
            try:
                for d in (depth, 0):
                    r = throughput("lk", 3.0, depth=d)
                    print(_throughput_line(label, r) + f" ratio {r['rate'] / raw['rate']:.3f}")
            finally:
                if base is None:
                    os.environ.pop("PYTHONPATH", None)
                else:
                    os.environ["PYTHONPATH"] = base
        sys.stdout.flush()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--role", choices=["pub", "sub"])
    parser.add_argument("--kind", choices=["raw", "hop", "lk"], default="lk")
    parser.add_argument("--size", type=int, default=100)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--count", type=int, default=0)
    parser.add_argument("--seconds", type=float, default=0.0)
    parser.add_argument("--expect", type=int, default=0)
    parser.add_argument("--first", action="store_true")
    parser.add_argument("--depth", type=int, default=10, help="subscription depth (0: KEEP_ALL)")
    parser.add_argument(
        "--throughput-rounds",
        type=int,
        default=0,
        help="only throughput: this many rounds of raw zenoh and each --tree, alternating",
    )
    parser.add_argument(
        "--tree",
        action="append",
        default=[],
        metavar="LABEL=DIR",
        help="a launchkit tree (exported with git archive) for --throughput-rounds, by PYTHONPATH",
    )
    parser.add_argument("--quick", action="store_true", help="fewer messages (a smoke run)")
    parser.add_argument("--steps", action="store_true", help="time each per-message step")
    args = parser.parse_args()
    if args.role == "pub":
        role_pub(args.kind, args.size, args.rate, args.count, args.seconds)
        return 0
    if args.role == "sub":
        role_sub(args.kind, args.expect, args.seconds, args.first, args.depth)
        return 0

    from launchkit.ros.router import start_router

    if args.steps:
        os.environ.setdefault("LAUNCHKIT_ROUTER", "tcp/127.0.0.1:7447")
        steps()
        return 0
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    endpoint = f"tcp/127.0.0.1:{port}"
    os.environ["LAUNCHKIT_ROUTER"] = endpoint
    router = start_router(endpoint)
    if args.throughput_rounds:
        try:
            throughput_rounds(args.throughput_rounds, args.tree, args.depth)
        finally:
            router.close()
        return 0
    scale = 10 if args.quick else 1
    print(f"# transport benchmark, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC")
    print(f"# {platform.platform()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    print(f"# router {endpoint}; both sides are peers behind it (rmw_zenoh topology)")
    results: dict[str, dict[str, Any]] = {}
    try:
        h50, h99, hn = latency("hop", 100, 1000.0, 3000 // scale)
        print(
            f"{'raw + hand-off':14s} 100 B  latency p50 {h50:8.1f} us  p99 {h99:8.1f} us  (n={hn})"
        )
        for kind, label in (("raw", "raw zenoh"), ("lk", "launchkit.ros")):
            r: dict[str, Any] = {}
            r["small"] = latency(kind, 100, 1000.0, 3000 // scale)
            r["large"] = latency(kind, 100_000, 100.0, 500 // scale)
            r["throughput"] = throughput(kind, 3.0 / (3 if args.quick else 1))
            if kind == "raw":
                r["throughput"]["depth"] = None
            else:
                r["keep_all"] = throughput(kind, 3.0 / (3 if args.quick else 1), depth=0)
            r["first"] = first_message(kind, 5 if not args.quick else 2)
            results[kind] = r
            s50, s99, sn = r["small"]
            l50, l99, ln = r["large"]
            starts, opens = r["first"]
            print(f"{label:14s} 100 B  latency p50 {s50:8.1f} us  p99 {s99:8.1f} us  (n={sn})")
            print(f"{label:14s} 100 KB latency p50 {l50:8.1f} us  p99 {l99:8.1f} us  (n={ln})")
            print(_throughput_line(label, r["throughput"]))
            if "keep_all" in r:
                print(_throughput_line(label, r["keep_all"]))
            print(
                f"{label:14s} first message: from process start median "
                f"{statistics.median(starts):6.1f} ms "
                f"(min {min(starts):.1f}, max {max(starts):.1f}); "
                f"from init/open median {statistics.median(opens):6.1f} ms "
                f"(min {min(opens):.1f}, max {max(opens):.1f})"
            )
    finally:
        router.close()
    ratio = results["lk"]["small"][0] / results["raw"]["small"][0]
    large_ratio = results["lk"]["large"][0] / results["raw"]["large"][0]
    print(
        f"100 KB p50 ratio {large_ratio:.2f}; throughput ratio "
        f"{results['lk']['throughput']['rate'] / results['raw']['throughput']['rate']:.2f} "
        "(launchkit/raw zenoh)"
    )
    first = statistics.median(results["lk"]["first"][1])
    print(
        f"transport: p50 ratio {ratio:.2f} (launchkit/raw zenoh), "
        f"throughput {results['lk']['throughput']['rate']:.0f} msg/s "
        f"(KEEP_ALL {results['lk']['keep_all']['rate']:.0f}), "
        f"first message {first:.1f} ms"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
