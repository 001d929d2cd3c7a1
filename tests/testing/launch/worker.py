"""Small processes with known behaviour for the test plugin's self-tests.

worker.py talk NAME [COUNT]   print COUNT lines, then "NAME waiting"; exit 0 on SIGINT
worker.py env                 print its LAUNCHKIT_* and ROS_* variables, then wait; exit 0 on
                              SIGINT
worker.py crash CODE          print "crashing", then exit with CODE
worker.py stubborn            ignore SIGINT (the launcher must escalate to SIGTERM)
worker.py very-stubborn       ignore SIGINT and SIGTERM (only SIGKILL ends it)
worker.py escape              start a grandchild that leaves the process group, print its pid
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys


def _exit_on_sigint() -> None:
    signal.signal(signal.SIGINT, lambda signum, frame: sys.exit(0))


def _announce_and_wait(text: str) -> None:
    print(text, flush=True)
    while True:
        signal.pause()


def main(argv: list[str]) -> int:
    mode = argv[0]
    if mode == "talk":
        _exit_on_sigint()
        name, count = argv[1], int(argv[2]) if len(argv) > 2 else 3
        for number in range(1, count + 1):
            print(f"{name} says hello {number}", flush=True)
        print(f"{name} to stderr", file=sys.stderr, flush=True)
        _announce_and_wait(f"{name} waiting")
    elif mode == "env":
        _exit_on_sigint()
        for variable, value in sorted(os.environ.items()):
            if variable.startswith(("LAUNCHKIT_", "ROS_")):
                print(f"{variable}={value}", flush=True)
        _announce_and_wait("env printed")
    elif mode == "crash":
        print("crashing", flush=True)
        return int(argv[1])
    elif mode == "stubborn":
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        _announce_and_wait("ignoring SIGINT")
    elif mode == "very-stubborn":
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        _announce_and_wait("ignoring SIGINT and SIGTERM")
    elif mode == "escape":
        _exit_on_sigint()
        code = "import os, signal; os.setpgid(0, 0); print(flush=True); signal.pause()"
        escaped = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE)
        assert escaped.stdout is not None
        escaped.stdout.readline()  # it has left the group
        _announce_and_wait(f"escaped pid {escaped.pid}")
    raise SystemExit(f"unknown mode {mode!r}")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
