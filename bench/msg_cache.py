"""What a process pays to use one message type, with the definitions' cache and without, and to
make one node.

    python bench/msg_cache.py [--runs 9] [--before DIR]

Each case is a fresh Python process. The ``Odometry`` cases get ``nav_msgs/msg/Odometry``, build
one, encode and decode it (what ``launchkit topic echo /odom`` needs of the message layer):

  * ``cache hit``: the cache folder (``LAUNCHKIT_CACHE_DIR``) already holds the definitions;
  * ``cache miss``: an empty cache folder each time (a user's first command after installing or
    upgrading rosbags: it reads rosbags' store and writes the cache);
  * ``--before``: an older tree's launchkit (a folder holding its package, e.g. from
    ``git archive``), which imports rosbags' Jazzy store every time;
  * floors: ``python -c pass`` and ``python -c "import numpy"`` (``Odometry``'s covariances are
    fixed-size arrays, which are numpy arrays, so those cases pay it).

The ``node`` cases make a node with a ``String`` publisher (its parameter services too) against
a router this script hosts, and destroy it: the start-up every node of a launch pays, ``--before``
with the older tree. A node needs no numpy (no value of a fixed-size array).

The cases take turns (one warm-up round), so a load change on this shared machine hits them all.
Each row is the median wall time and the median CPU time (user + system, from the children's
resource usage), the honest measure on a loaded machine.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from launchkit.ros.router import start_router
from launchkit.testing._isolation import free_loopback_port, router_endpoint

PY = sys.executable
USE = (
    "from launchkit.ros.msgs import deserialize, get_message, serialize\n"
    "odom = get_message('nav_msgs/msg/Odometry')()\n"
    "deserialize(serialize(odom), 'nav_msgs/msg/Odometry')\n"
)
NODE = (
    "import launchkit.ros as ros\n"
    "from launchkit.ros.msgs import get_message\n"
    "ros.init()\n"
    "node = ros.Node('bench_node')\n"
    "node.create_publisher(get_message('std_msgs/msg/String'), 'chatter', 10)\n"
    "node.destroy_node()\n"
    "ros.shutdown()\n"
)
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def run(code: str, env: dict[str, str]) -> tuple[float, float]:
    """Wall and CPU seconds of ``python -c code`` (from a temporary folder, so that ``-c``'s
    current-folder entry on ``sys.path`` does not shadow ``--before``'s tree)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([PY, "-c", code], env=env, check=True, cwd=tempfile.gettempdir())
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main() -> None:
    """Measure the cases and print one row each."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=9, help="interleaved rounds")
    parser.add_argument("--before", type=Path, help="a folder with an older launchkit package")
    args = parser.parse_args()
    router = start_router(router_endpoint(free_loopback_port()))
    with tempfile.TemporaryDirectory(prefix="lk-bench-cache-") as tmp:
        warm = {**ENV, "LAUNCHKIT_CACHE_DIR": str(Path(tmp) / "warm")}
        node_env = {**warm, "LAUNCHKIT_ROUTER": router.endpoint}
        fresh = iter(range(1 << 30))

        def cold() -> tuple[float, float]:
            env = {**ENV, "LAUNCHKIT_CACHE_DIR": str(Path(tmp) / f"cold{next(fresh)}")}
            return run(USE, env)

        cases: dict[str, Callable[[], tuple[float, float]]] = {
            "python -c pass": lambda: run("pass", ENV),
            "python -c 'import numpy'": lambda: run("import numpy", ENV),
            "Odometry, cache hit": lambda: run(USE, warm),
            "Odometry, cache miss": cold,
            "node": lambda: run(NODE, node_env),
        }
        if args.before is not None:
            older = {**ENV, "PYTHONPATH": str(args.before.resolve())}
            cases["Odometry, --before"] = lambda: run(USE, older)
            cases["node, --before"] = lambda: run(NODE, {**node_env, **older})
        for action in cases.values():
            action()
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in cases}
        for _ in range(args.runs):
            for name, action in cases.items():
                samples[name].append(action())
    router.close()
    print(f"{'case':28s} | {'wall ms':>8s} | {'CPU ms':>7s} | load {os.getloadavg()[0]:.1f}")
    for name, values in samples.items():
        wall = statistics.median(v[0] for v in values) * 1000
        cpu = statistics.median(v[1] for v in values) * 1000
        print(f"{name:28s} | {wall:8.0f} | {cpu:7.0f}")


if __name__ == "__main__":
    main()
