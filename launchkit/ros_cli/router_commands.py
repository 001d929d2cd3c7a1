"""``launchkit router``: run a router in the foreground, or start, inspect and stop the shared
background one (as ``ros2 daemon start|status|stop`` does for the ROS 2 daemon)."""

from __future__ import annotations

import argparse
import signal
import threading
import time
from typing import Any

from launchkit.envvars import ROUTER, ROUTER_IDLE_TIMEOUT
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.ros.endpoints import host_port, is_loopback, router_endpoint
from launchkit.ros.federation import RouterOptions, describe
from launchkit.ros.port_owner import (
    command_line,
    connections_to,
    find_listener,
    pids_holding,
    user_name,
)
from launchkit.ros.shared_router import (
    SharedRouterState,
    idle_timeout,
    start_shared_router,
    stop_shared_router,
)
from launchkit.ros_cli.router_options import add_federation_options, federation_options


def add_parser(commands: Any) -> None:
    """Register the ``router`` command."""
    p = commands.add_parser(
        "router",
        help="run a ROS (Zenoh) router, or start/status/stop the shared background one",
        description="Without a verb: host a router in this terminal until Ctrl-C. "
        "start: start the shared background router (what any launchkit process does when it "
        "finds no router on loopback); status: what answers at the endpoint; stop: stop the "
        "shared background router.",
    )
    p.add_argument(
        "verb", nargs="?", choices=("start", "status", "stop"), metavar="start|status|stop"
    )
    p.add_argument(
        "--router",
        metavar="tcp/HOST:PORT",
        help=f"where to listen (default ${ROUTER} or tcp/127.0.0.1:7447)",
    )
    p.add_argument(
        "--idle-timeout",
        type=float,
        metavar="SECONDS",
        help="exit after this long with nothing connected (0: never; default: never in the "
        f"foreground, ${ROUTER_IDLE_TIMEOUT} or 300 for the shared router)",
    )
    add_federation_options(p)
    p.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(run=_run)


def _run(args: argparse.Namespace) -> int:
    endpoint = router_endpoint(args.router)
    if args.idle_timeout is not None and not args.idle_timeout >= 0:
        raise UserError(f"--idle-timeout {args.idle_timeout}", expected="seconds >= 0")
    if args.verb == "status":
        return _status(endpoint)
    if args.verb == "stop":
        return _stop(endpoint)
    options = federation_options(args)
    if args.verb == "start":
        if not options.empty:
            raise UserError(
                "the shared router takes its federation settings from the LAUNCHKIT_ROUTER_* "
                "variables only",
                expected="`launchkit router --listen/--connect ...` (in the foreground) instead",
            )
        return _start(endpoint, args.idle_timeout)
    return _foreground(endpoint, args.idle_timeout or 0.0, options)


def _start(endpoint: str, idle: float | None) -> int:
    if not is_loopback(endpoint):
        raise UserError(
            f"the shared router listens on loopback only, not at {endpoint}",
            expected="tcp/127.0.0.1:PORT (for other addresses: `launchkit router` with --listen)",
        )
    seconds = idle_timeout() if idle is None else idle
    pid = start_shared_router(endpoint, seconds)
    if pid is None:
        print(f"a ROS router already answers at {endpoint}")
        return _status(endpoint)
    print(f"started the shared ROS router at {endpoint} (pid {pid})")
    return 0


def _status(endpoint: str) -> int:
    """What answers at ``endpoint``: exit 0 when a router does, 1 when nothing does."""
    host, port = host_port(endpoint)
    listener = find_listener(host, port)
    shared = SharedRouterState.read(endpoint)
    if listener is None:
        print(f"no ROS router answers at {endpoint}")
        return 1
    pids = pids_holding(listener.inode)
    sessions = connections_to(port)
    if shared is not None and (not pids or shared.pid in pids):
        up = time.time() - shared.started
        lifetime = (
            f"exits after {shared.idle_timeout:g} s with nothing connected"
            if shared.idle_timeout
            else "runs until `launchkit router stop`"
        )
        print(f"shared ROS router at {endpoint}: running (pid {shared.pid}, up {up:.0f} s)")
        print(f"  {sessions} connection(s) now; {lifetime}")
        print(f"  log: {shared.log}")
        return 0
    who = ", ".join(f"pid {pid} ({command_line(pid) or '?'})" for pid in pids) or "a process"
    print(f"ROS router at {endpoint}: {who}, user {user_name(listener.uid)}")
    print(f"  {sessions} connection(s) now; not the shared background router")
    return 0


def _stop(endpoint: str) -> int:
    state = stop_shared_router(endpoint)
    if state is not None:
        print(f"stopped the shared ROS router at {endpoint} (pid {state.pid})")
        return 0
    host, port = host_port(endpoint)
    listener = find_listener(host, port)
    if listener is None:
        print(f"no shared ROS router runs at {endpoint}")
        return 0
    pids = ", ".join(str(pid) for pid in pids_holding(listener.inode)) or "unknown"
    raise RuntimeLaunchError(
        f"the router at {endpoint} is not the shared background router (pid {pids}): "
        "stop the launch or `launchkit router` that hosts it"
    )


def _say(level: str, message: str) -> None:
    print(f"[{level.upper()}] [router]: {message}", flush=True)


def _foreground(endpoint: str, idle: float, options: RouterOptions) -> int:
    from launchkit.ros.router import start_router

    handle = start_router(endpoint, options=options, report=_say)
    if not handle.hosted:
        raise RuntimeLaunchError(f"a router already listens at {endpoint}")
    print(f"[INFO] [router]: listening at {handle.endpoint} (Ctrl-C to stop)", flush=True)
    for line in describe(options):
        _say("info", line)
    for warning in handle.warnings:
        _say("warn", warning)
    stop = threading.Event()

    def on_signal(signum: int, frame: Any) -> None:
        stop.set()

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    last_used = time.monotonic()
    try:
        while not stop.wait(1.0):
            if handle.sessions():
                last_used = time.monotonic()
            elif idle and time.monotonic() - last_used >= idle:
                print(f"[INFO] [router]: nothing connected for {idle:g} s: exiting", flush=True)
                break
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        handle.close()
    print("[INFO] [router]: stopped", flush=True)
    return 0
