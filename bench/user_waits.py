"""Issue 15's table in one run: each place a user waits, beside its floor (run by hand).

    python bench/user_waits.py [--runs 5] [--bringups 3] [--camera-seconds 10]
                               [--only PART] [--before DIR]

Every row is the median of interleaved runs (the command and its floor alternate, so a load
change on this shared machine hits both), and is printed with its ratio and the issue's target:

  * ``launchkit run`` of an empty file against ``python -c pass`` (same interpreter);
  * 100 ``echo`` executables, start to exit, against a Python process that starts the same 100
    with a plain Popen loop and waits for them (start to exit);
  * ``launchkit topic list`` / ``node list`` with a router and a talker up, then beside the
    robot (the bring-up below), against ``python -c "import zenoh"``;
  * ``launchkit topic echo /odom --once`` beside the robot, against one /odom period;
  * pub/sub p50 latency of 100 B messages at 1 kHz, launchkit.ros against raw zenoh
    (bench/transport.py's processes), beside raw zenoh whose callback only hands the bytes to
    the main thread through the executor's queue (the floor of rclpy's threading);
  * README line 1 (``launchkit run robot_wheel gazebo_and_rviz.launch.xml``, here with
    ``start_rviz:=false`` so runs do not fight over the viewer's port) to the first /odom;
  * the seed camera (800x800 at 30 Hz, paced at real time) subscribed: frames per wall second,
    TinyRenderer and EGL (bench/bringup.py's camera case).

``--before DIR`` (a folder holding an older ``launchkit`` package, e.g. from ``git archive``)
adds that tree's ``launchkit run`` of the empty file and of the 100 ``echo``, ``topic echo
/odom --once`` and pub/sub latency to the same interleaved rounds, so before and after share the
machine's load; ``--only odom`` alternates bring-ups of the two trees to the first /odom (and
nothing else). Commands run from the temporary folder: ``python -m`` puts the current folder
first on ``sys.path``, which from the repository would shadow ``--before``'s tree with this one.

Bytecode is written and used (PYTHONDONTWRITEBYTECODE is dropped for the children), as after
``pip install``. The message definitions' cache (``LAUNCHKIT_CACHE_DIR``) is a temporary folder
of the run, filled by its first process as a user's first command fills theirs (so the rows are
with the cache; ``bench/msg_cache.py`` measures the first use). Each row says the machine's
load average when it was measured.
"""

from __future__ import annotations

import argparse
import os
import platform
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bringup
import transport

ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
PY = sys.executable
LAUNCHKIT = [PY, "-m", "launchkit"]
POPEN_LOOP = (
    "import subprocess\n"
    "procs = [subprocess.Popen(['echo', 'hi'], stdout=subprocess.DEVNULL) for _ in range(100)]\n"
    "for p in procs: p.wait()\n"
)
TALKER = Path(__file__).resolve().parents[1] / "tests" / "ros" / "nodes" / "talker.py"


#: The environment that runs ``--before``'s launchkit instead of this one (None: no such tree).
BEFORE: dict[str, str] | None = None


def wall(argv: list[str], env: dict[str, str]) -> float:
    """Seconds from spawning ``argv`` to its exit (output discarded; a failure is fatal)."""
    start = time.perf_counter()
    subprocess.run(
        argv,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=env,
        check=True,
        cwd=tempfile.gettempdir(),
    )
    return time.perf_counter() - start


def before(env: dict[str, str]) -> dict[str, str]:
    """``env`` running ``--before``'s launchkit."""
    assert BEFORE is not None
    return {**env, **BEFORE}


def interleaved(cases: dict[str, Callable[[], float]], runs: int) -> dict[str, float]:
    """Median of each case over ``runs`` rounds, the cases taking turns (one warm-up round)."""
    for action in cases.values():
        action()
    samples: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(runs):
        for name, action in cases.items():
            samples[name].append(action())
    return {name: statistics.median(values) for name, values in samples.items()}


def row(what: str, value: str, floor: str, ratio: str, target: str, met: bool | None) -> None:
    """One printed result line."""
    verdict = "n/a" if met is None else ("HIT" if met else "MISS")
    load = os.getloadavg()[0]
    print(
        f"{what:44s} | {value:>10s} | {floor:>24s} | {ratio:>7s} | {target:>12s} | "
        f"{verdict:4s} | load {load:.1f}",
        flush=True,
    )


def free_endpoint() -> str:
    """A free loopback endpoint."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return f"tcp/127.0.0.1:{sock.getsockname()[1]}"


def startup_rows(runs: int) -> None:
    """The empty launch file and 100 echo executables."""
    with tempfile.TemporaryDirectory() as tmp:
        env = {**ENV, "ROS_LOG_DIR": str(Path(tmp) / "log")}
        empty = Path(tmp) / "empty.launch.xml"
        empty.write_text("<launch/>\n")
        hundred = Path(tmp) / "n100.launch.xml"
        hundred.write_text("<launch>\n" + '<executable cmd="echo hi"/>\n' * 100 + "</launch>\n")
        cases: dict[str, Callable[[], float]] = {
            "pass": lambda: wall([PY, "-c", "pass"], env),
            "empty": lambda: wall([*LAUNCHKIT, "run", str(empty)], env),
            "loop": lambda: wall([PY, "-c", POPEN_LOOP], env),
            "hundred": lambda: wall([*LAUNCHKIT, "run", str(hundred)], env),
        }
        if BEFORE is not None:
            cases["empty_before"] = lambda: wall([*LAUNCHKIT, "run", str(empty)], before(env))
            cases["hundred_before"] = lambda: wall([*LAUNCHKIT, "run", str(hundred)], before(env))
        m = interleaved(cases, runs)
    rows = [
        ("launchkit run, empty file", "empty", "pass", "python -c pass", 2.5),
        ("100 echo executables, start to exit", "hundred", "loop", "Popen loop", 1.5),
    ]
    for what, key, floor, floor_name, target in rows:
        names = [("  --before: " + what, key + "_before")] if BEFORE is not None else []
        for label, measured in [*names, (what, key)]:
            ratio = m[measured] / m[floor]
            row(
                label,
                f"{m[measured] * 1000:.0f} ms",
                f"{floor_name} {m[floor] * 1000:.0f} ms",
                f"{ratio:.2f}x",
                f"<= {target}x",
                ratio <= target,
            )


def cli_rows(runs: int, endpoint: str, label: str, echo: bool) -> None:
    """``topic list``, ``node list`` (and ``topic echo /odom --once``) against the router."""
    env = {**ENV, "LAUNCHKIT_ROUTER": endpoint}
    cases: dict[str, Callable[[], float]] = {
        "zenoh": lambda: wall([PY, "-c", "import zenoh"], env),
        "topic": lambda: wall([*LAUNCHKIT, "topic", "list"], env),
        "node": lambda: wall([*LAUNCHKIT, "node", "list"], env),
    }
    echo_argv = [*LAUNCHKIT, "topic", "echo", "/odom", "--once"]
    if echo:
        cases["echo"] = lambda: wall(echo_argv, env)
    if echo and BEFORE is not None:
        cases["echo_before"] = lambda: wall(echo_argv, before(env))
    m = interleaved(cases, runs)
    floor = f"import zenoh {m['zenoh'] * 1000:.0f} ms"
    for key, what in (("topic", "topic list"), ("node", "node list")):
        row(
            f"launchkit {what} ({label})",
            f"{m[key]:.3f} s",
            floor,
            f"{m[key] / m['zenoh']:.1f}x",
            "<= 0.25 s",
            m[key] <= 0.25,
        )
    if echo:
        row(
            "launchkit topic echo /odom --once (robot up)",
            f"{m['echo']:.3f} s",
            "one /odom period",
            "",
            "<= 0.4 s",
            m["echo"] <= 0.4,
        )
    if echo and BEFORE is not None:
        row(
            "  --before: topic echo /odom --once",
            f"{m['echo_before']:.3f} s",
            "one /odom period",
            "",
            "<= 0.4 s",
            m["echo_before"] <= 0.4,
        )


def idle_cli_rows(runs: int) -> None:
    """The CLI with a router and one talker up, nothing else running."""
    from launchkit.ros.router import start_router

    endpoint = free_endpoint()
    router = start_router(endpoint)
    talker = subprocess.Popen(
        [PY, str(TALKER)],
        env={**ENV, "LAUNCHKIT_ROUTER": endpoint},
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        assert talker.stdout is not None
        while "talker ready" not in talker.stdout.readline():
            pass
        cli_rows(runs, endpoint, "router + talker", echo=False)
    finally:
        talker.terminate()
        talker.wait(10)
        router.close()


def latency_rows(rounds: int) -> None:
    """p50 one-way latency of 100 B at 1 kHz, raw zenoh and launchkit.ros taking turns (and
    ``--before``'s launchkit.ros, in the same rounds)."""
    endpoint = free_endpoint()
    os.environ["LAUNCHKIT_ROUTER"] = endpoint
    from launchkit.ros.router import start_router

    router = start_router(endpoint)
    raw, hop, lk, old = [], [], [], []
    try:
        for _ in range(rounds):
            raw.append(transport.latency("raw", 100, 1000.0, 2000)[0])
            hop.append(transport.latency("hop", 100, 1000.0, 2000)[0])
            lk.append(transport.latency("lk", 100, 1000.0, 2000)[0])
            if BEFORE is not None:
                # transport.py's children inherit os.environ: its PYTHONPATH picks the tree
                saved = os.environ.get("PYTHONPATH")
                os.environ["PYTHONPATH"] = BEFORE["PYTHONPATH"]
                try:
                    old.append(transport.latency("lk", 100, 1000.0, 2000)[0])
                finally:
                    if saved is None:
                        del os.environ["PYTHONPATH"]
                    else:
                        os.environ["PYTHONPATH"] = saved
    finally:
        router.close()
    r, k = statistics.median(raw), statistics.median(lk)
    row(
        "pub/sub p50 latency, 100 B at 1 kHz",
        f"{k:.0f} us",
        f"raw zenoh {r:.0f} us",
        f"{k / r:.2f}x",
        "<= 1.3x",
        k / r <= 1.3,
    )
    h = statistics.median(hop)
    row(
        "  raw zenoh + the executor's hand-off alone",
        f"{h:.0f} us",
        f"raw zenoh {r:.0f} us",
        f"{h / r:.2f}x",
        "",
        None,
    )
    if old:
        b = statistics.median(old)
        row(
            "  --before: pub/sub p50 latency",
            f"{b:.0f} us",
            f"raw zenoh {r:.0f} us",
            f"{b / r:.2f}x",
            "<= 1.3x",
            b / r <= 1.3,
        )
    print(
        "  per round (raw / hand-off alone / after"
        + (" / before" if old else "")
        + ") us: "
        + "; ".join(
            " / ".join(f"{v:.0f}" for v in vals)
            for vals in zip(raw, hop, lk, *([old] if old else []), strict=True)
        ),
        flush=True,
    )


def odom_period(bring: Any) -> float:
    """Seconds between /odom messages (over 20 of them)."""
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    stamps: list[float] = []
    sub = bring.node.create_subscription(
        Odometry, "/odom", lambda _m: stamps.append(time.perf_counter()), 10
    )
    bring._spin_until(lambda: len(stamps) >= 21, 30, "21 /odom messages")
    bring.node.destroy_subscription(sub)
    return (stamps[20] - stamps[0]) / 20


def first_odom(env: dict[str, str] | None = None) -> float:
    """Seconds from ``launchkit run`` of README line 1 to its first /odom (one bring-up)."""
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    bring = bringup.BringUp(env=env)
    try:
        return float(bring.first(Odometry, "/odom")[1])
    finally:
        bring.stop()


def odom_rows(bringups: int) -> None:
    """README line 1 to the first /odom alone, interleaved with ``--before``'s tree if given."""
    cases: dict[str, Callable[[], float]] = {"after": first_odom}
    if BEFORE is not None:
        cases["before"] = lambda: first_odom(BEFORE)
    samples: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(bringups):
        for name, action in cases.items():
            samples[name].append(action())
    for name in sorted(cases, reverse=True):
        first = statistics.median(samples[name])
        runs = " ".join(f"{value:.2f}" for value in samples[name])
        row(
            f"{'  --before: ' if name == 'before' else ''}README line 1 to first /odom",
            f"{first:.2f} s",
            f"runs: {runs}",
            "",
            "<= 1.0 s",
            first <= 1.0,
        )


def bringup_rows(runs: int, bringups: int, camera_seconds: float, cli_only: bool = False) -> None:
    """README line 1 to the first /odom; the CLI beside the robot; the camera's frame rate
    (``cli_only``: one bring-up and the CLI beside it)."""
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    firsts = []
    for attempt in range(1 if cli_only else bringups):
        bring = bringup.BringUp()
        try:
            firsts.append(bring.first(Odometry, "/odom")[1])
            if attempt == 0:
                period = odom_period(bring)
                print(f"# /odom period beside the robot: {period * 1000:.1f} ms", flush=True)
                cli_rows(runs, bring.router, "robot up", echo=True)
        finally:
            bring.stop()
    if cli_only:
        return
    first = statistics.median(firsts)
    row(
        "README line 1 to first /odom",
        f"{first:.2f} s",
        "",
        "",
        "<= 1.0 s",
        first <= 1.0,
    )
    for egl, target in ((False, 15.0), (True, 30.0)):
        rates = [bringup.camera_case(egl, "1.0", camera_seconds)[1] for _ in range(bringups)]
        fps = statistics.median(rates)
        row(
            f"camera 800x800 @30 Hz, {'EGL' if egl else 'TinyRenderer'}",
            f"{fps:.1f} fps",
            "30 fps",
            "",
            f">= {target:.0f} fps",
            fps >= target,
        )


def main() -> None:
    """Measure every row and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="interleaved rounds per command")
    parser.add_argument("--bringups", type=int, default=3, help="robot bring-ups per row")
    parser.add_argument("--camera-seconds", type=float, default=10.0)
    parser.add_argument(
        "--only",
        choices=["startup", "cli", "latency", "robot", "robot-cli", "odom"],
        help="one part (robot-cli: one bring-up and the CLI beside it; odom: --bringups "
        "bring-ups to the first /odom, alternating with --before's)",
    )
    parser.add_argument("--before", type=Path, help="a folder with an older launchkit package")
    args = parser.parse_args()
    os.environ.pop("PYTHONDONTWRITEBYTECODE", None)  # for the bring-ups' processes too
    with tempfile.TemporaryDirectory(prefix="lk-bench-cache-") as cache:
        os.environ["LAUNCHKIT_CACHE_DIR"] = ENV["LAUNCHKIT_CACHE_DIR"] = cache
        measure(args)


def measure(args: argparse.Namespace) -> None:
    """The rows ``args`` ask for."""
    if args.before is not None:
        global BEFORE
        BEFORE = {"PYTHONPATH": str(args.before.resolve())}
    print(
        f"# {platform.node()} {platform.machine()}, {os.cpu_count()} cores, Python "
        f"{platform.python_version()}, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC",
        flush=True,
    )
    print(
        f"{'where a user waits':44s} | {'launchkit':>10s} | {'floor, same run':>24s} | "
        f"{'ratio':>7s} | {'target':>12s} | met? | load",
        flush=True,
    )
    if args.only in (None, "startup"):
        startup_rows(args.runs)
    if args.only in (None, "cli"):
        idle_cli_rows(args.runs)
    if args.only in (None, "latency"):
        latency_rows(max(3, args.runs))
    if args.only in (None, "robot"):
        bringup_rows(args.runs, args.bringups, args.camera_seconds)
    if args.only == "odom":
        odom_rows(args.bringups)
    if args.only == "robot-cli":
        bringup_rows(args.runs, args.bringups, args.camera_seconds, cli_only=True)


if __name__ == "__main__":
    main()
