"""The shared background router's process: ``python -m launchkit.ros.router_daemon ENDPOINT``.

Started by :func:`launchkit.ros.shared_router.start_shared_router`, through a ``sh`` that
puts it in the background and exits at once, in a session of its own: so it is nobody's child
and holds no terminal. Once the router listens (or cannot) it prints ``ready PID`` (or
``error: ...``) on its standard output, the starter's pipe, and from then on writes to a log
file, with ``/`` as its working folder. It runs until SIGTERM/SIGINT (``launchkit router
stop``) or until nothing has been connected to it for the idle timeout, and removes its state
file on the way out.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
import time
from typing import TYPE_CHECKING

from launchkit.errors import LaunchkitError
from launchkit.ros.endpoints import host_port, validate_endpoint
from launchkit.ros.rundir import router_file
from launchkit.ros.shared_router import SharedRouterState

if TYPE_CHECKING:
    from launchkit.ros.router import RouterHandle

CHECK_PERIOD = 1.0  # seconds between looks at the number of connected sessions
START_GRACE = 10.0  # seconds the process that started the router has to connect to it


def main(argv: list[str]) -> int:
    """Run the shared router at ``argv[0]``; see the module's docstring."""
    parser = argparse.ArgumentParser(prog="launchkit.ros.router_daemon")
    parser.add_argument("endpoint")
    parser.add_argument("--idle-timeout", type=float, required=True)
    args = parser.parse_args(argv)
    try:
        endpoint = validate_endpoint(args.endpoint)
        log = router_file(*host_port(endpoint), "log")
        log_fd = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC, 0o600)
    except (LaunchkitError, OSError) as error:
        print(f"error: {error}", flush=True)
        return 1
    os.chdir("/")
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    return _serve(endpoint, args.idle_timeout, str(log), log_fd)


def _to_log(log_fd: int) -> None:
    """From now on stdout and stderr go to the log (this closes the starter's pipe)."""
    sys.stdout.flush()
    sys.stderr.flush()
    os.dup2(log_fd, 1)
    os.dup2(log_fd, 2)
    os.close(log_fd)


def _serve(endpoint: str, idle: float, log: str, log_fd: int) -> int:
    from launchkit.ros.logging import get_logger
    from launchkit.ros.router import start_router

    logger = get_logger("router")
    stop = threading.Event()

    def on_signal(signum: int, _frame: object) -> None:
        stop.set()

    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, on_signal)

    def report(level: str, message: str) -> None:
        getattr(logger, level)(message)

    try:
        # federation settings, if any, come from the LAUNCHKIT_ROUTER_* variables
        handle = start_router(endpoint, lock=False, report=report)  # the starter holds the lock
    except LaunchkitError as error:
        print(f"error: {error.message}", flush=True)
        return 1
    if not handle.hosted:
        print(f"error: a router already listens at {endpoint}", flush=True)
        return 1
    state = SharedRouterState(os.getpid(), endpoint, idle, log, time.time())
    state.write()
    print(f"ready {os.getpid()}", flush=True)
    _to_log(log_fd)
    lifetime = f"exits after {idle:g} s with nothing connected" if idle else "runs until stopped"
    logger.info(f"shared ROS router listening at {endpoint} (pid {os.getpid()}; {lifetime})")
    for warning in handle.warnings:
        logger.warn(warning)
    try:
        _run_until_idle(handle, idle, stop)
        if not stop.is_set():
            logger.info(f"nothing connected for {idle:g} s: exiting")
    finally:
        state.remove()
        handle.close()
    logger.info("stopped")
    sys.stderr.flush()
    return 0


def _run_until_idle(handle: RouterHandle, idle: float, stop: threading.Event) -> None:
    # counted from a little later than now: the starter connects only once it is told
    last_used = time.monotonic() + max(0.0, START_GRACE - idle)
    while not stop.wait(CHECK_PERIOD):
        now = time.monotonic()
        if handle.sessions() > 0:
            last_used = now
        elif idle and now - last_used >= idle:
            return


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
