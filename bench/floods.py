"""Benchmark: the launcher under children that flood their output (run by hand; results go in
docs/benchmarks.md).

    python bench/floods.py [--repeat 3]

Each as the median of --repeat runs, beside a baseline measured in the same run:
  * 200 MB without a newline (``head -c 200M /dev/zero``) read and logged by the launcher, until
    it exits on its own, vs the same bytes through ``cat`` into a file (the floor);
  * 100 MB of 2-byte lines (``yes | head -c 100M``), the same way;
  * SIGINT to exit while ``yes`` floods (output="log" and output="screen" to a pipe read and
    dropped), vs SIGINT to exit with a sleeping child;
  * the launcher's peak RSS (VmHWM) in those runs.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

LAUNCHKIT = [sys.executable, "-m", "launchkit", "run"]


def write(directory: Path, body: str) -> Path:
    """A launch file with ``body`` inside <launch>."""
    path = directory / "flood.launch.xml"
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


def peak_rss_mb(pid: int) -> float:
    """The process's peak resident set (VmHWM) so far, in MB."""
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    return 0.0


def run_to_end(path: Path, env: dict[str, str]) -> tuple[float, float]:
    """Seconds until ``launchkit run`` exits on its own, and its peak RSS in MB."""
    start = time.perf_counter()
    proc = subprocess.Popen([*LAUNCHKIT, str(path)], stdout=subprocess.DEVNULL, env=env)
    peak = 0.0
    while proc.poll() is None:
        try:
            peak = max(peak, peak_rss_mb(proc.pid))
        except OSError:
            break
        time.sleep(0.05)
    proc.wait()
    return time.perf_counter() - start, peak


def stop_latency(path: Path, env: dict[str, str], flood_for: float) -> tuple[float, float]:
    """Seconds from SIGINT to the launcher's exit after ``flood_for`` s of running, and its
    peak RSS in MB."""
    proc = subprocess.Popen([*LAUNCHKIT, str(path)], stdout=subprocess.PIPE, env=env)
    assert proc.stdout is not None
    started = False
    deadline = time.monotonic() + 30
    while not started and time.monotonic() < deadline:
        started = b"process started" in proc.stdout.readline()
    drain = subprocess.Popen(["cat"], stdin=proc.stdout, stdout=subprocess.DEVNULL)
    time.sleep(flood_for)
    peak = peak_rss_mb(proc.pid)
    start = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    proc.wait()
    latency = time.perf_counter() - start
    drain.wait()
    proc.stdout.close()
    return latency, peak


def cat_floor(command: str, directory: Path) -> float:
    """Seconds for ``command | cat > file``: the bytes moved with nothing done to them."""
    start = time.perf_counter()
    with open(directory / "floor.out", "wb") as out:
        subprocess.run(["sh", "-c", f"{command} | cat"], stdout=out, check=True)
    return time.perf_counter() - start


def main() -> None:
    """Run every measurement and print a table."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"{datetime.datetime.now():%Y-%m-%d %H:%M} on {platform.node()}, {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as scratch:
        directory = Path(scratch)
        env = {**os.environ, "ROS_LOG_DIR": str(directory / "log")}
        rows: list[tuple[str, str, str]] = []
        for label, command in (
            ("200 MB, no newline", "head -c 200M /dev/zero"),
            ("100 MB of 'y' lines", "yes | head -c 100M"),
        ):
            path = write(directory, f'<executable name="flood" cmd="sh -c \'{command}\'"/>')
            runs = [run_to_end(path, env) for _ in range(args.repeat)]
            floor = statistics.median(cat_floor(command, directory) for _ in range(args.repeat))
            wall = statistics.median(r[0] for r in runs)
            rss = max(r[1] for r in runs)
            rows.append(
                (
                    f"{label}, read and logged",
                    f"{wall:.2f} s, peak {rss:.0f} MB",
                    f"cat: {floor:.2f} s",
                )
            )
        idle = write(directory, '<executable name="idle" cmd="sleep 300"/>')
        baseline = [stop_latency(idle, env, 1.0) for _ in range(args.repeat)]
        for mode in ("log", "screen"):
            path = write(directory, f'<executable name="yes" cmd="yes" output="{mode}"/>')
            runs = [stop_latency(path, env, 3.0) for _ in range(args.repeat)]
            latency = statistics.median(r[0] for r in runs) * 1000
            rss = max(r[1] for r in runs)
            idle_ms = statistics.median(r[0] for r in baseline) * 1000
            rows.append(
                (
                    f"SIGINT to exit, `yes` flooding (output={mode})",
                    f"{latency:.0f} ms, peak {rss:.0f} MB",
                    f"sleeping child: {idle_ms:.0f} ms",
                )
            )
    width = max(len(r[0]) for r in rows)
    for name, value, floor in rows:
        print(f"{name:<{width}}  {value:<24}  {floor}")


if __name__ == "__main__":
    sys.exit(main())
