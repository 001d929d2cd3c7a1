"""Run a command several times while busy processes load every core (run by hand).

    python bench/under_load.py [--hogs 2] [--repeat 5] -- python -m pytest -n 2 -q

Starts ``--hogs`` processes spinning ``while 1: pass`` (default: one per core), runs the command
``--repeat`` times in a row, stops the hogs however it ends, and prints each run's exit status
and wall time with the machine and date. It exits 0 only if every run did.

The suite must pass like this (issue #9); the wait rules' self-test is
``tests/testing/stress_waits.py``, which repeats issue #9's test ``LAUNCHKIT_STRESS_RUNS`` times
(default 200)::

    python bench/under_load.py -- python -m pytest -n 2 -q -p no:cacheprovider \\
        tests/testing/stress_waits.py
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import time

HOG = "while 1: pass"


def main(argv: list[str]) -> int:
    """Parse the options, load the machine, run the command; 0 if every run passed."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--hogs", type=int, default=os.cpu_count() or 2, help="busy processes")
    parser.add_argument("--repeat", type=int, default=1, help="runs of the command in a row")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND ARGS...")
    options = parser.parse_args(argv)
    command = options.command[1:] if options.command[:1] == ["--"] else options.command
    if not command:
        parser.error("no command given (put it after --)")
    print(
        f"# {datetime.datetime.now():%Y-%m-%d %H:%M} on {platform.node()} "
        f"({os.cpu_count()} cores, Python {platform.python_version()}), "
        f"{options.hogs} CPU hog(s): {' '.join(command)}",
        flush=True,
    )
    hogs = [subprocess.Popen([sys.executable, "-c", HOG]) for _ in range(options.hogs)]
    results: list[tuple[int, float]] = []
    try:
        for run in range(1, options.repeat + 1):
            start = time.monotonic()
            status = subprocess.call(command)
            results.append((status, time.monotonic() - start))
            print(f"# run {run}: exit status {status} in {results[-1][1]:.0f} s", flush=True)
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    passed = sum(1 for status, _ in results if status == 0)
    print(f"# {passed} of {len(results)} run(s) passed under load", flush=True)
    return 0 if passed == len(results) == options.repeat else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
