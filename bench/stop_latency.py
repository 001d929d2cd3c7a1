"""Benchmark: how long after SIGINT each long-running command has exited (run by hand; results
in docs/benchmarks.md). Target: within 1 s, even with every core busy.

    python bench/stop_latency.py [--runs 5] [--hogs 2]

Starts a router and a 50 Hz talker, then, ``--runs`` times, each command alone with ``--hogs``
processes spinning: waits until it prints that it runs, sends SIGINT and measures the wall
time until it has exited, the CPU time it spent after the signal, and its status. Prints the
median and worst per command. Wall time under load depends on the scheduler and on what else
runs; the CPU time spent stopping does not, and is what a busy machine has to find.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import signal
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

NODES = Path(__file__).resolve().parents[1] / "tests" / "ros" / "nodes"
URDF = "robot_description:=<robot name='r'><link name='a'/></robot>"
COMMANDS = {
    "topic echo": ["topic", "echo", "/chatter"],
    "topic hz": ["topic", "hz", "/chatter"],
    "topic pub": ["topic", "pub", "/x", "std_msgs/msg/String", "{data: a}", "-r", "20"],
    "router": ["router", "--router", "tcp/127.0.0.1:{port}"],
    "exec robot_state_publisher": [
        *("exec", "robot_state_publisher", "robot_state_publisher", "--ros-args", "-p", URDF)
    ],
    "exec joint_state_publisher": ["exec", "joint_state_publisher", "joint_state_publisher"],
}


def free_port() -> int:
    """A free TCP port on loopback."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def stop_time(argv: list[str], env: dict[str, str]) -> tuple[float, float, int]:
    """Start ``launchkit ARGV``, wait for its first line, SIGINT it: (seconds to exit, CPU
    seconds spent after the signal, status)."""
    process = subprocess.Popen(
        [sys.executable, "-m", "launchkit", *argv],
        env={**env, "RCUTILS_LOGGING_USE_STDOUT": "1"},
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    assert process.stdout is not None
    process.stdout.readline()
    time.sleep(0.5)  # steady state, not start-up
    before = _cpu_seconds(process.pid)
    start = time.monotonic()
    process.send_signal(signal.SIGINT)
    _, wait_status, usage = os.wait4(process.pid, 0)
    elapsed = time.monotonic() - start
    process.returncode = os.waitstatus_to_exitcode(wait_status)
    process.stdout.close()
    return elapsed, usage.ru_utime + usage.ru_stime - before, process.returncode


def main(argv: list[str]) -> int:
    """Measure every command; print a table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--hogs", type=int, default=os.cpu_count() or 2)
    options = parser.parse_args(argv)
    router = f"tcp/127.0.0.1:{free_port()}"
    env = {**os.environ, "LAUNCHKIT_ROUTER": router, "PYTHONUNBUFFERED": "1"}
    print(
        f"# {datetime.datetime.now():%Y-%m-%d %H:%M} on {platform.node()} "
        f"({os.cpu_count()} cores, Python {platform.python_version()}), "
        f"{options.hogs} CPU hog(s), {options.runs} run(s) per command"
    )
    started: list[subprocess.Popen[str]] = []
    hogs: list[subprocess.Popen[bytes]] = []
    try:
        for args in (["-m", "launchkit", "router"], [str(NODES / "talker.py")]):
            process = subprocess.Popen(
                [sys.executable, *args], env=env, stdout=subprocess.PIPE, text=True
            )
            started.append(process)
            assert process.stdout is not None
            process.stdout.readline()
        spin = [sys.executable, "-c", "while 1: pass"]
        hogs += [subprocess.Popen(spin) for _ in range(options.hogs)]
        print(
            "| command | wall, median | wall, worst | CPU after SIGINT, median | exit statuses |"
            "\n|---|---|---|---|---|"
        )
        for name, args in COMMANDS.items():
            times, cpu, statuses = [], [], set()
            for _ in range(options.runs):
                argv_ = [arg.replace("{port}", str(free_port())) for arg in args]
                elapsed, spent, status = stop_time(argv_, env)
                times.append(elapsed)
                cpu.append(spent)
                statuses.add(status)
            print(
                f"| {name} | {statistics.median(times):.2f} s | {max(times):.2f} s "
                f"| {statistics.median(cpu):.2f} s | {', '.join(map(str, sorted(statuses)))} |",
                flush=True,
            )
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
        for process in reversed(started):
            process.send_signal(signal.SIGINT)
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
