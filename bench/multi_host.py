"""Multi-host benchmark: two hosts (network namespaces joined by a veth pair), run by hand as
root: ``python bench/multi_host.py [--quick]``.

It measures, with ``bench/transport.py``'s publisher and subscriber roles (launchkit.ros,
100 B messages; latency is the receiver's CLOCK_MONOTONIC minus the sender's, one clock for both
namespaces):
  * one router: publisher and subscriber on host A behind A's router (peers then talk directly,
    as on one machine);
  * two routers: publisher on A, subscriber on B, routers linked over TCP (the data goes
    publisher -> router A -> router B -> subscriber);
  * the same over mutual TLS;
and the time for a process to start: ``launchkit run`` of a file whose one process prints a
line, from the launcher's start to that line on its console, with the process on this host and
on host B through its agent. Each figure is the median of ``--runs`` runs.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "multihost"))
from netns import Host, Hosts, Proc, netns_unavailable  # noqa: E402

TRANSPORT = str(ROOT / "bench" / "transport.py")
WARMUP = 200
LOCAL = "tcp/127.0.0.1:7447"


def _role(host: Host, *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        ["ip", "netns", "exec", host.name, sys.executable, TRANSPORT, *args],
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, "LAUNCHKIT_ROUTER": LOCAL},
    )


def _ready(proc: subprocess.Popen[str]) -> None:
    assert proc.stdout is not None
    line = proc.stdout.readline()
    if "ready" not in line:
        raise RuntimeError(f"a role said {line!r}")


def _pair(sub_host: Host, pub_host: Host, sub: list[str], pub: list[str]) -> dict[str, Any]:
    receiver = _role(sub_host, "--role", "sub", "--kind", "lk", *sub)
    _ready(receiver)
    sender = _role(pub_host, "--role", "pub", "--kind", "lk", *pub)
    _ready(sender)
    out, _ = receiver.communicate(timeout=120)
    sender.communicate(timeout=60)
    return dict(json.loads(out.strip().splitlines()[-1]))


def _pct(values: list[int], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] / 1000.0


def transport(sub_host: Host, pub_host: Host, count: int, seconds: float) -> dict[str, float]:
    """Latency p50/p99 (us) of 100 B at 1 kHz and throughput (msg/s) from pub to sub."""
    total = count + WARMUP
    lat = _pair(
        sub_host,
        pub_host,
        ["--expect", str(count), "--seconds", str(total / 1000 + 20)],
        ["--size", "100", "--rate", "1000", "--count", str(total)],
    )["latencies_ns"]
    rate = _pair(
        sub_host,
        pub_host,
        ["--seconds", str(seconds + 20)],
        ["--size", "100", "--rate", "0", "--seconds", str(seconds)],
    )["rate"]
    return {"p50": _pct(lat, 0.5), "p99": _pct(lat, 0.99), "rate": float(rate), "n": len(lat)}


def routers(hosts: Hosts, *security: str) -> list[Proc]:
    """Router A listening on the link, router B connected to it."""
    proto = "tls" if security else "tcp"
    link = f"{proto}/{hosts.a.address}:7448"
    a = hosts.a.launchkit("router", "--router", LOCAL, "--listen", link, *security[:2])
    a.expect("listening at")
    b = hosts.b.launchkit("router", "--router", LOCAL, "--connect", link, *security[2:])
    b.expect(f"linked to the router at {link}", timeout=60)
    return [a, b]


def start_time(hosts: Hosts, machine: str, folder: Path, runs: int) -> list[float]:
    """Seconds from ``launchkit run`` to its process's first line, ``runs`` times."""
    launch = folder / f"probe-{machine or 'local'}.launch.xml"
    launch.write_text(
        f'<launch><group machine="{machine}"><executable name="probe" output="screen" '
        "cmd=\"sh -c 'echo up; exec sleep 60'\"/></group></launch>\n"
    )
    env = {"LAUNCHKIT_AGENT_KEY": str(folder / "agent.key")}
    times = []
    for _ in range(runs):
        started = time.monotonic()
        run = hosts.a.launchkit(
            "run", str(launch), "--connect", f"tcp/{hosts.b.address}:7448", env=env
        )
        run.expect("[probe-1] up", timeout=60)
        times.append(time.monotonic() - started)
        run.stop()
    return times


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer messages (a smoke run)")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    reason = netns_unavailable()
    if reason is not None:
        print(f"multi_host: cannot run here: {reason}")
        return 2
    count, seconds = (300, 1.0) if args.quick else (3000, 3.0)
    print(f"# multi-host benchmark, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC")
    print(f"# {platform.platform()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    results: dict[str, list[dict[str, float]]] = {"one": [], "two": [], "mtls": []}
    folder = Path(tempfile.mkdtemp(prefix="lk-bench-"))
    sys.path.insert(0, str(ROOT / "tests" / "multihost"))
    from certs import Authority

    ca = Authority("bench-ca")
    certs_a = ca.host_folder(folder / "a", "host-a", "10.231.0.1")
    certs_b = ca.host_folder(folder / "b", "host-b", "10.231.0.2")
    secure = ("--mtls", str(certs_a), "--mtls", str(certs_b))
    for _ in range(args.runs):
        for name, security in (("one", None), ("two", ()), ("mtls", secure)):
            hosts = Hosts()
            try:
                routers(hosts, *(security or ()))
                receiver = hosts.a if security is None else hosts.b
                results[name].append(transport(receiver, hosts.a, count, seconds))
            finally:
                hosts.close()
    for name, label in (
        ("one", "one router (both on A)"),
        ("two", "two routers, TCP link"),
        ("mtls", "two routers, mutual TLS"),
    ):
        runs = results[name]
        p50 = statistics.median(r["p50"] for r in runs)
        p99 = statistics.median(r["p99"] for r in runs)
        rate = statistics.median(r["rate"] for r in runs)
        print(f"{label:26s} 100 B p50 {p50:7.1f} us  p99 {p99:8.1f} us  {rate:9.0f} msg/s")
    base = statistics.median(r["p50"] for r in results["one"])
    two = statistics.median(r["p50"] for r in results["two"])
    print(f"two routers / one router: p50 x{two / base:.2f}")

    hosts = Hosts()
    try:
        agent = hosts.b.launchkit(
            "agent", "--name", "hostb", "--listen", f"tcp/{hosts.b.address}:7448",
            env={"LAUNCHKIT_AGENT_KEY": str(folder / "agent.key")},
        )  # fmt: skip
        agent.expect("agent hostb ready", timeout=60)
        local = start_time(hosts, "", folder, args.runs)
        remote = start_time(hosts, "hostb", folder, args.runs)
    finally:
        hosts.close()
    print(
        f"process start, launcher to first line: here median {statistics.median(local):.2f} s "
        f"(min {min(local):.2f}); on host B median {statistics.median(remote):.2f} s "
        f"(min {min(remote):.2f})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
