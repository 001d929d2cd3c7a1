"""Benchmark: lockstep simulated time (run by hand; results go in docs/benchmarks.md).

    python bench/lockstep.py [--runs 10] [--seconds 20] [--only speed,camera,overhead,repeat]

The launch is tests/lockstep/launch/scenario.launch.xml: the seed robot (seed 001's launch file
without the viewer: server, lidar, diff drive, camera node, robot_state_publisher), a node
driving it from a sim-time timer and a node printing /odom at 3 s of simulated time.

  * speed: simulated seconds per wall second in ``--lockstep`` without a camera subscriber
    (target >= 10x), from two runs ending at different ``--until`` (start-up cancels out);
  * camera: the same with the camera's image subscribed, and its frames per simulated second
    (target >= 1x real time at 30 frames per simulated second);
  * overhead: CPU seconds of the whole launch (launcher and every process) for ``--seconds``
    of simulated time at ``--lockstep --rtf 1.0`` against today's real-time run for as long
    (target <= +10 %);
  * repeat: the printed /odom over ``--runs`` runs, quiet and then with two busy processes
    keeping both cores loaded (target: 1 distinct answer each).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import resource
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

LAUNCH = Path(__file__).resolve().parent.parent / "tests/lockstep/launch/scenario.launch.xml"


def free_port() -> int:
    """A free TCP port on loopback."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def children_cpu() -> float:
    """CPU seconds of every child process waited for so far (and of what they waited for)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def launch(
    *options: str, args: tuple[str, ...] = (), wall_limit: float | None = None
) -> tuple[str, float, float]:
    """Run the scenario with ``options`` and launch arguments ``args``; its output, wall
    seconds and CPU seconds. With ``wall_limit`` it is stopped by Ctrl-C after that many wall
    seconds."""
    env = {
        **os.environ,
        "PYTHON": sys.executable,
        "ROS_LOG_DIR": tempfile.mkdtemp(prefix="lockstep-bench-"),
    }
    command = [sys.executable, "-m", "launchkit", "run"]
    command += [*options, "--router", f"tcp/127.0.0.1:{free_port()}", str(LAUNCH), *args]
    cpu = children_cpu()
    started = time.perf_counter()
    with subprocess.Popen(
        command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    ) as proc:
        try:
            out, _ = proc.communicate(timeout=wall_limit)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGINT)
            out, _ = proc.communicate(timeout=60)
    wall = time.perf_counter() - started
    return out, wall, children_cpu() - cpu


def speed(until: float, *args: str) -> tuple[float, str]:
    """Simulated seconds per wall second past start-up: runs to 2 s and to ``until``."""
    _, short, _ = launch("--lockstep", "--until", "2", args=args)
    out, long, _ = launch("--lockstep", "--until", str(until), args=args)
    return (until - 2.0) / (long - short), out


def frames_per_sim_second(out: str) -> str:
    counts = [line.split() for line in out.splitlines() if "FRAMES" in line]
    if len(counts) < 3:
        return "no frames counted"
    first, last = counts[1], counts[-1]  # from the second simulated second on
    frames = int(last[-3]) - int(first[-3])
    seconds = (int(last[-1]) - int(first[-1])) / 1e9
    return f"{frames / seconds:.1f} frames per simulated second"


def odom_answers(runs: int) -> set[str]:
    answers = set()
    for _ in range(runs):
        out, _, _ = launch("--lockstep", "--until", "3.5")
        lines = [line.split("ODOM at", 1)[1] for line in out.splitlines() if "ODOM at" in line]
        answers.add(lines[0] if lines else "no /odom printed")
    return answers


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--only", default="speed,camera,overhead,repeat")
    args = parser.parse_args()
    only = set(args.only.split(","))
    print(
        f"# {datetime.date.today()} {platform.node()} {os.cpu_count()} CPUs, Python "
        f"{platform.python_version()}"
    )
    if "speed" in only:
        factor, _ = speed(2.0 + args.seconds)
        print(f"lockstep, no camera subscriber: {factor:.2f}x real time (target >= 10x)")
    if "camera" in only:
        factor, out = speed(2.0 + args.seconds / 4, "camera:=true")
        print(
            f"lockstep, camera subscribed: {factor:.2f}x real time, "
            f"{frames_per_sim_second(out)} (target >= 1x at 30)"
        )
    if "overhead" in only:
        until = 2.0 + args.seconds
        _, wall, lockstep_cpu = launch("--lockstep", "--rtf", "1.0", "--until", str(until))
        _, _, realtime_cpu = launch(wall_limit=wall)
        print(
            f"CPU for {wall:.1f} s of wall time: lockstep at --rtf 1.0 {lockstep_cpu:.1f} s, "
            f"real-time run {realtime_cpu:.1f} s: {100 * (lockstep_cpu / realtime_cpu - 1):+.1f} %"
            " (target <= +10 %)"
        )
    if "repeat" in only:
        quiet = odom_answers(args.runs)
        print(f"quiet: {len(quiet)} distinct /odom answer(s) in {args.runs} runs (target 1)")
        burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
        try:
            loaded = odom_answers(args.runs)
        finally:
            for burner in burners:
                burner.kill()
                burner.wait()
        print(
            f"both cores busy: {len(loaded)} distinct answer(s) in {args.runs} runs; "
            f"{'the same as' if loaded == quiet else 'NOT the same as'} quiet (target 1, same)"
        )


if __name__ == "__main__":
    main()
