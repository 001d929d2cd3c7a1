"""The same rclpy talker and listener on launchkit's rclpy (over a Zenoh router) and on the real
rclpy (the ros-jazzy wheels, over Fast DDS): latency and CPU per message (issue 24's target: at
most the real rclpy's).

The talker publishes ``std_msgs/String`` messages holding their send time at ``--rate`` Hz once
the listener is matched; the listener prints the latency percentiles; each prints the CPU time
it spent between its first and last message, so the CPU per message is both processes' sum
over the count. Needs CPython 3.11 with the test extra (the real rclpy)::

    python bench/rclpy_talker_listener.py [--count 2000] [--rate 200] [--runs 3]
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import random
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from launchkit.ros import face
from launchkit.ros.router import start_router
from launchkit.testing._isolation import free_loopback_port, router_endpoint

TALKER = """
import resource, sys, time
import rclpy
from std_msgs.msg import String

def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime

count, rate = int(sys.argv[1]), float(sys.argv[2])
rclpy.init()
node = rclpy.create_node("bench_talker")
publisher = node.create_publisher(String, "bench_chatter", 1000)
while publisher.get_subscription_count() == 0:
    rclpy.spin_once(node, timeout_sec=0.05)
time.sleep(0.5)  # the listener's subscription is matched both ways
start = cpu()
period = 1.0 / rate
due = time.monotonic()
for _ in range(count):
    publisher.publish(String(data=str(time.time_ns())))
    due += period
    time.sleep(max(0.0, due - time.monotonic()))
print(f"talker cpu {cpu() - start:.4f}", flush=True)
time.sleep(1.0)
rclpy.shutdown()
"""

LISTENER = """
import resource, sys, time
import rclpy
from std_msgs.msg import String

def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime

count = int(sys.argv[1])
rclpy.init()
node = rclpy.create_node("bench_listener")
latencies = []
first_cpu = []

def heard(message):
    latencies.append(time.time_ns() - int(message.data))
    if len(latencies) == 1:
        first_cpu.append(cpu())

node.create_subscription(String, "bench_chatter", heard, 1000)
print("listening", flush=True)
deadline = time.monotonic() + 120
while len(latencies) < count and time.monotonic() < deadline:
    rclpy.spin_once(node, timeout_sec=0.1)
used = cpu() - first_cpu[0] if first_cpu else 0.0
print(f"listener received {len(latencies)} cpu {used:.4f}", flush=True)
print("latencies_us " + " ".join(str(n // 1000) for n in latencies), flush=True)
rclpy.shutdown()
"""


def run_once(
    flavour: str, env: dict[str, str], folder: Path, count: int, rate: float
) -> dict[str, float]:
    """One talker/listener exchange; its figures."""
    listener = subprocess.Popen(
        [sys.executable, str(folder / "listener.py"), str(count)],
        env=env,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert listener.stdout is not None
    assert listener.stdout.readline().strip() == "listening", flavour
    talker = subprocess.run(
        [sys.executable, str(folder / "talker.py"), str(count), str(rate)],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    out, _ = listener.communicate(timeout=300)
    talker_cpu = float(talker.stdout.split("talker cpu ")[1].split()[0])
    received_line = next(line for line in out.splitlines() if line.startswith("listener"))
    received = int(received_line.split()[2])
    listener_cpu = float(received_line.split()[4])
    latencies = [int(v) for v in out.split("latencies_us ")[1].split()]
    latencies.sort()
    return {
        "received": received,
        "p50_us": statistics.median(latencies),
        "p99_us": latencies[int(len(latencies) * 0.99) - 1],
        "cpu_us_per_msg": (talker_cpu + listener_cpu) / max(1, received) * 1e6,
    }


def main() -> int:
    """Run both flavours ``--runs`` times, alternating, and print the figures."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=2000)
    parser.add_argument("--rate", type=float, default=200.0)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    base = {k: v for k, v in os.environ.items() if not k.startswith(("LAUNCHKIT_", "ROS_"))}
    base.pop("PYTHONPATH", None)
    endpoint = router_endpoint(free_loopback_port())
    router = start_router(endpoint)
    domain = str(random.randint(100, 200))
    flavours = {
        "launchkit": {**base, "LAUNCHKIT_RCLPY": "launchkit", "LAUNCHKIT_ROUTER": endpoint},
        "real rclpy (Fast DDS)": {
            **base,
            "LAUNCHKIT_RCLPY": "ros",
            "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp",
            "ROS_DOMAIN_ID": domain,
        },
    }
    flavours["launchkit"].update(face.environment(flavours["launchkit"]))
    now = datetime.datetime.now(datetime.timezone.utc)
    print(
        f"{platform.node()} {platform.machine()} {os.cpu_count()} cores, Python "
        f"{platform.python_version()}, {now:%Y-%m-%d %H:%M} UTC, "
        f"load {os.getloadavg()[0]:.1f}; {args.count} messages at {args.rate:g} Hz"
    )
    try:
        with tempfile.TemporaryDirectory() as name:
            folder = Path(name)
            (folder / "talker.py").write_text(TALKER)
            (folder / "listener.py").write_text(LISTENER)
            for run in range(args.runs):
                for flavour, env in flavours.items():
                    got = run_once(flavour, env, folder, args.count, args.rate)
                    print(
                        f"run {run + 1} {flavour:22} received {got['received']:5} "
                        f"latency p50 {got['p50_us']:7.0f} us p99 {got['p99_us']:7.0f} us "
                        f"cpu {got['cpu_us_per_msg']:6.0f} us/msg"
                    )
    finally:
        router.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
