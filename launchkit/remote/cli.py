"""``launchkit agent``: run this host's share of launches started on other hosts."""

from __future__ import annotations

import argparse
import signal
import socket
import sys
import threading
from pathlib import Path
from types import FrameType

from launchkit.envvars import AGENT_KEY, ROUTER
from launchkit.errors import LaunchkitError, RuntimeLaunchError
from launchkit.remote.agent import Agent
from launchkit.remote.keys import default_key_path, load_key
from launchkit.remote.protocol import check_name
from launchkit.ros.endpoints import router_endpoint
from launchkit.ros.federation import describe
from launchkit.ros.router import start_router
from launchkit.ros_cli.router_options import add_federation_options, federation_options


def build_parser() -> argparse.ArgumentParser:
    """``launchkit agent``'s options."""
    parser = argparse.ArgumentParser(
        prog="launchkit agent",
        description="Run the processes that launches on other hosts mark for this host "
        '(<group machine="NAME">). See docs/multi-host.md.',
    )
    parser.add_argument(
        "--name",
        help="this host's name in launch files (default: the host name, up to its first dot)",
    )
    parser.add_argument(
        "--router",
        metavar="tcp/HOST:PORT",
        help=f"this host's router, hosted or joined (default ${ROUTER} or tcp/127.0.0.1:7447)",
    )
    parser.add_argument(
        "--key",
        metavar="FILE",
        help=f"the agent key shared with the launchers (default ${AGENT_KEY} or "
        "~/.config/launchkit/agent.key, made on first start)",
    )
    add_federation_options(parser)
    parser.add_argument("--debug", action="store_true", help=argparse.SUPPRESS)
    return parser


def _say(level: str, message: str) -> None:
    print(f"[{level.upper()}] [agent]: {message}", flush=True)


def main(argv: list[str]) -> int:
    """Run the agent until SIGINT/SIGTERM; its processes are stopped first."""
    args = build_parser().parse_args(argv)
    name = check_name(args.name or socket.gethostname().split(".")[0] or "localhost")
    endpoint = router_endpoint(args.router)
    options = federation_options(args)
    key_path = Path(args.key).expanduser() if args.key else default_key_path()
    created = not key_path.exists()
    key = load_key(key_path, create=True)
    if created:
        _say("info", f"made the agent key {key_path}: copy it to the hosts that launch here")

    router = start_router(endpoint, options=options, report=_say)
    for line in describe(options):
        _say("info", line)
    for warning in router.warnings:
        _say("warn", warning)
    if not router.hosted and not options.empty:
        _say(
            "warn",
            f"joined the router already at {endpoint}: --listen/--connect/--tls/--mtls/--access "
            "apply only to a router the agent starts (stop that one, or use another --router)",
        )
    agent = Agent(name, key, endpoint, _say)
    stop = threading.Event()
    interrupts = [0]

    def on_signal(signum: int, frame: FrameType | None) -> None:
        interrupts[0] += 1
        if interrupts[0] > 1:
            agent.escalate()
        stop.set()
        agent.wake()

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        agent.open()
        verb = "hosting" if router.hosted else "joined"
        _say("info", f"agent {name} ready ({verb} the router at {endpoint}; Ctrl-C to stop)")
        agent.run(stop)
    except LaunchkitError:
        raise
    except OSError as error:
        raise RuntimeLaunchError(f"agent {name}: {error}") from None
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        agent.close()
        router.close()
    _say("info", "stopped")
    sys.stdout.flush()
    return 0
