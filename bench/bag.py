"""Benchmark: recording and playing bags (run by hand; results go in docs/benchmarks.md).

    python bench/bag.py [--seconds 20] [--bulk 300]

1. **Robot recording.** `launchkit run robot_wheel gazebo_and_rviz.launch.xml start_rviz:=false`
   on its own router; `launchkit bag record` of the seed camera (800x800 rgb8; the recorder's
   subscription makes it render), the lidar, /tf and /tf_static for ``--seconds``. Messages lost
   are counted against the publishers' sequence numbers (rmw_zenoh's attachment carries one per
   publisher; the recorder reports the gaps) and against the recorder's queue (drops); the bag's
   own counts are checked against what the recorder received.
2. **Playback timing.** That bag played at 1x into a fresh router; a probe subscribes to every
   topic raw and takes, per message, the player's publish time (the attachment's source
   timestamp) and its own receive time. Error = that time minus the bag's timestamp, less the
   median of that difference (the constant start offset); p50/p99 of its absolute value.
3. **Throughput of 1 MB messages.** ``--bulk`` messages of 1 MiB (`sensor_msgs/Image`, random
   bytes: incompressible) published flat out (reliable, keep all: never dropped by the
   publisher) and recorded by `launchkit bag record` with a queue that holds them all: MB/s from
   the first publish until all are in the file. Then the bag played as fast as it goes
   (`--rate 1000`) to a probe: MB/s over the span of the deliveries. Plus the bag writer alone
   and rosbags' reader alone, in this process, for comparison.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

MB = 1_000_000


def free_port() -> int:
    """A free TCP port on loopback."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def launchkit(router: str, *args: str, log: Path | None = None) -> subprocess.Popen[bytes]:
    """``launchkit ARGS`` on ``router`` in its own process group."""
    out = log.open("wb") if log else subprocess.DEVNULL
    return subprocess.Popen(
        [sys.executable, "-m", "launchkit", *args],
        env={**os.environ, "LAUNCHKIT_ROUTER": router},
        stdin=subprocess.DEVNULL,
        stdout=out,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )


def stop(process: subprocess.Popen[bytes], timeout: float = 60) -> int:
    """Ctrl-C, then wait; SIGKILL the group if it hangs."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
    try:
        return process.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        return process.wait()


def wait_for_line(log: Path, text: str, timeout: float) -> None:
    """Wait until ``log`` has a line containing ``text``."""
    deadline = time.monotonic() + timeout
    while text not in log.read_text(errors="replace"):
        if time.monotonic() > deadline:
            raise SystemExit(f"no {text!r} in {log} within {timeout} s")
        time.sleep(0.1)


def percentile(values: list[float], q: float) -> float:
    """The ``q`` quantile (0..1) of ``values``."""
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


class Probe:
    """A node of this process on ``router``; raw subscriptions keep (topic, info, size)."""

    def __init__(self, router: str) -> None:
        import launchkit.ros as ros

        self.ros = ros
        self.context = ros.Context(router=router)
        self.context.init([])
        self.node = ros.Node("bench_probe", context=self.context, start_parameter_services=False)
        self.got: list[tuple[str, dict[str, int], int]] = []

    def subscribe_bag(self, bag: Path) -> int:
        """Subscribe to every topic of ``bag`` with the QoS the player offers; message count."""
        from rosbags.rosbag2 import Reader

        from launchkit.bag.qos import offer_for_recorded
        from launchkit.ros.msgs import get_message

        with Reader(bag) as reader:
            for connection in reader.connections:
                qos = offer_for_recorded(
                    connection.topic, connection.ext.offered_qos_profiles, print
                )
                self.node.create_subscription(
                    get_message(connection.msgtype),
                    connection.topic,
                    lambda data, info, topic=connection.topic: self.got.append(
                        (topic, info, len(data))
                    ),
                    qos,
                    raw=True,
                )
            return int(reader.message_count)

    def spin_until(self, done: Any, timeout: float, what: str) -> None:
        deadline = time.monotonic() + timeout
        while not done():
            if time.monotonic() > deadline:
                raise SystemExit(f"timed out waiting for {what}")
            self.ros.spin_once(self.node, timeout_sec=0.05)

    def close(self) -> None:
        self.context.shutdown()


def report_numbers(log: Path) -> tuple[int, int, int]:
    """(received, dropped, missed) from the recorder's closing report."""
    match = re.search(
        r"Received (\d+) messages .*?; (\d+) dropped .*?, (\d+) missed", log.read_text()
    )
    if not match:
        raise SystemExit(f"no report in {log}:\n{log.read_text()[-2000:]}")
    received, dropped, missed = map(int, match.groups())
    return received, dropped, missed


def bag_counts(bag: Path) -> tuple[dict[str, int], int, int]:
    """Messages per topic, total bytes and duration (ns) of ``bag``."""
    from rosbags.rosbag2 import Reader

    with Reader(bag) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        size = sum(len(d) for _, _, d in reader.messages())
        return counts, size, reader.duration


def record_robot(work: Path, seconds: float) -> Path:
    """Part 1: the robot's camera, lidar and tf recorded for ``seconds``."""
    router = f"tcp/127.0.0.1:{free_port()}"
    robot = launchkit(
        router,
        "run",
        "--router",
        router,
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        "start_rviz:=false",
        log=work / "robot.log",
    )
    bag, log = work / "robot_bag", work / "record.log"
    try:
        wait_for_line(work / "robot.log", "Successfully spawned entity", 120)
        recorder = launchkit(
            router,
            "bag",
            "record",
            "/camera1/image_raw",
            "/scan",
            "/tf",
            "/tf_static",
            "-o",
            str(bag),
            log=log,
        )
        wait_for_line(log, "Subscribed to topic '/camera1/image_raw'", 60)
        started = time.monotonic()
        time.sleep(seconds)
        code = stop(recorder)
        elapsed = time.monotonic() - started
    finally:
        stop(robot)
    received, dropped, missed = report_numbers(log)
    counts, size, duration = bag_counts(bag)
    print(f"robot recording: {elapsed:.1f} s, recorder exit {code}")
    print(f"  bag: {sum(counts.values())} messages {counts}, {size / MB:.1f} MB of messages")
    print(f"  recorder: received {received}, dropped {dropped} (queue full), missed {missed}")
    print(f"  bag holds every message received: {sum(counts.values()) == received - dropped}")
    print(f"  write rate {size / MB / (duration / 1e9):.1f} MB/s over {duration / 1e9:.1f} s")
    frames = counts.get("/camera1/image_raw", 0)
    print(f"  camera frames {frames} ({frames / (duration / 1e9):.1f} per s)")
    return bag


def playback_timing(bag: Path) -> None:
    """Part 2: playback timing error at 1x."""
    from rosbags.rosbag2 import Reader

    router_handle, router = start_router()
    probe = Probe(router)
    try:
        expected = probe.subscribe_bag(bag)
        player = launchkit(router, "bag", "play", str(bag), log=bag.parent / "play.log")
        probe.spin_until(lambda: len(probe.got) >= expected, 300, f"{expected} messages")
        stop(player)
    finally:
        probe.close()
        router_handle.close()
    with Reader(bag) as reader:
        stamps: dict[str, list[int]] = {}
        for connection, stamp, _ in reader.messages():
            stamps.setdefault(connection.topic, []).append(stamp)
    position: dict[str, int] = {}
    publish_offsets, receive_offsets = [], []
    for topic, info, _ in probe.got:
        index = position.get(topic, 0)
        position[topic] = index + 1
        stamp = stamps[topic][index]
        publish_offsets.append(info["source_timestamp"] - stamp)
        receive_offsets.append(info["received_timestamp"] - stamp)
    for name, offsets in (("publish", publish_offsets), ("delivery", receive_offsets)):
        middle = statistics.median(offsets)
        errors = [abs(o - middle) / 1e6 for o in offsets]
        print(
            f"playback {name} timing error at 1x: p50 {percentile(errors, 0.5):.3f} ms, "
            f"p99 {percentile(errors, 0.99):.3f} ms, max {max(errors):.3f} ms "
            f"({len(errors)} messages)"
        )


def start_router() -> tuple[Any, str]:
    """A router hosted by this process on a free port."""
    from launchkit.ros.router import start_router as start

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    return start(endpoint), endpoint


def bulk(work: Path, count: int) -> None:
    """Part 3: 1 MiB messages through the recorder and the player."""
    import numpy as np
    from launchkit.ros.msgs.sensor_msgs.msg import Image

    from launchkit.ros.qos import HistoryPolicy, QoSProfile

    payload = np.random.default_rng(1).integers(0, 255, 1 << 20, dtype=np.uint8)
    image = Image(height=1024, width=1024, encoding="mono8", step=1024, data=payload)
    router_handle, router = start_router()
    bag, log = work / "bulk_bag", work / "bulk_record.log"
    probe = Probe(router)
    try:
        publisher = probe.node.create_publisher(
            Image, "/bulk", QoSProfile(depth=10, history=HistoryPolicy.KEEP_ALL)
        )
        # a queue that holds them all: the figure is how fast they reach the disk, not drops
        recorder = launchkit(
            router, "bag", "record", "/bulk", "-o", str(bag), "--max-cache-size", str(4 << 30),
            log=log,
        )  # fmt: skip
        wait_for_line(log, "Subscribed to topic '/bulk'", 60)
        probe.spin_until(lambda: publisher.get_subscription_count() > 0, 10, "the recorder")
        started = time.perf_counter()
        for _ in range(count):
            publisher.publish(image)
        sent = time.perf_counter() - started
        storage = bag / f"{bag.name}.mcap"  # each 1 MiB message closes (and flushes) a chunk
        deadline = time.monotonic() + 300
        while storage.stat().st_size < count * (1 << 20) and time.monotonic() < deadline:
            time.sleep(0.005)
        written = time.perf_counter() - started
        stop(recorder)
    finally:
        probe.close()
        router_handle.close()
    received, dropped, missed = report_numbers(log)
    counts, size, _ = bag_counts(bag)
    rate = count * (1 << 20) / MB / sent
    print(f"1 MiB messages: published {count} in {sent:.2f} s ({rate:.0f} MB/s)")
    print(f"  record: received {received}, dropped {dropped}, missed {missed}; bag {counts}")
    print(f"  record throughput {size / MB / written:.0f} MB/s (first publish to all on disk)")

    router_handle, router = start_router()
    probe = Probe(router)
    try:
        expected = probe.subscribe_bag(bag)
        player = launchkit(router, "bag", "play", str(bag), "--rate", "1000")
        # keep-last publishers drop what a congested link cannot take (rmw_zenoh's rule, and
        # DDS keep-last writers overwrite): wait for the player to end, then for the stragglers
        probe.spin_until(lambda: player.poll() is not None, 120, "the player to finish")
        settled = [len(probe.got), time.monotonic()]

        def quiet() -> bool:
            if len(probe.got) != settled[0]:
                settled[:] = [len(probe.got), time.monotonic()]
            return len(probe.got) >= expected or time.monotonic() - settled[1] > 2.0

        probe.spin_until(quiet, 60, "the last deliveries")
    finally:
        probe.close()
        router_handle.close()
    first = min(i["received_timestamp"] for _, i, _ in probe.got)
    last = max(i["received_timestamp"] for _, i, _ in probe.got)
    total = sum(n for _, _, n in probe.got)
    print(
        f"  play throughput {total / MB / ((last - first) / 1e9):.0f} MB/s "
        f"({len(probe.got)} of {expected} messages delivered)"
    )
    alone(work, image)


def alone(work: Path, image: Any) -> None:
    """The bag writer and rosbags' reader without transport (this process)."""
    from rosbags.rosbag2 import Reader

    from launchkit.bag.metadata import TopicRecord
    from launchkit.bag.storage import BagWriter, WriterOptions
    from launchkit.ros.msgs import message_definition, serialize, type_hash

    data = serialize(image)
    name = "sensor_msgs/msg/Image"
    path = work / "alone"
    started = time.perf_counter()
    writer = BagWriter(path, WriterOptions())
    topic = writer.add_topic(TopicRecord("/bulk", name, type_hash(name)), message_definition(name))
    for n in range(300):
        writer.write(topic, n, data)
    writer.close()
    wrote = time.perf_counter() - started
    started = time.perf_counter()
    with Reader(path) as reader:
        size = sum(len(d) for _, _, d in reader.messages())
    read = time.perf_counter() - started
    print(
        f"  bag writer alone {300 * len(data) / MB / wrote:.0f} MB/s, "
        f"rosbags reader alone {size / MB / read:.0f} MB/s"
    )


def main() -> None:
    """Run the three parts and print their figures."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="robot recording length")
    parser.add_argument("--bulk", type=int, default=300, help="1 MiB messages to push through")
    parser.add_argument("--keep", action="store_true", help="keep the bags (path printed)")
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench-bag-"))
    print(
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, load {os.getloadavg()[0]:.1f}"
    )
    try:
        bag = record_robot(work, args.seconds)
        playback_timing(bag)
        bulk(work, args.bulk)
    finally:
        if args.keep:
            print(f"bags in {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
