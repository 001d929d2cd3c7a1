"""``launchkit router``: run a standalone Zenoh router until interrupted."""

from __future__ import annotations

import argparse
import signal
import threading
from typing import Any

from launchkit.envvars import ROUTER
from launchkit.errors import RuntimeLaunchError
from launchkit.ros.router import start_router


def add_parser(commands: Any) -> None:
    """Register the ``router`` command."""
    p = commands.add_parser("router", help="run a standalone ROS (Zenoh) router")
    p.add_argument(
        "--router",
        metavar="tcp/HOST:PORT",
        help=f"where to listen (default ${ROUTER} or tcp/127.0.0.1:7447)",
    )
    p.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(run=_run)


def _run(args: argparse.Namespace) -> int:
    handle = start_router(args.router)
    if not handle.hosted:
        raise RuntimeLaunchError(f"a router already listens at {handle.endpoint}")
    stop = threading.Event()

    def on_signal(signum: int, frame: Any) -> None:
        stop.set()

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        print(f"[INFO] [router]: listening at {handle.endpoint} (Ctrl-C to stop)", flush=True)
        while not stop.wait(1.0):
            pass
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        handle.close()
    print("[INFO] [router]: stopped", flush=True)
    return 0
