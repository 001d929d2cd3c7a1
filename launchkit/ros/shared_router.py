"""The shared background router: started by the first launchkit process that finds none.

Like ``ros2 daemon``, it belongs to no terminal: :mod:`launchkit.ros.router_daemon` runs it in
a session of its own, detached from whoever started it, writing to a log file in the user's
runtime folder (:mod:`launchkit.ros.rundir`), and it exits once nothing has been connected to
it for ``$LAUNCHKIT_ROUTER_IDLE_TIMEOUT`` seconds. Two processes starting at once end with one
router: the start is done under a lock file, and whoever finds a router already listening
joins it.

What a process does when it needs a router (:func:`ensure_router`):

* one of this user's listens at the endpoint: join it (another user's: refuse, see
  :mod:`launchkit.ros.router_access`);
* none, the endpoint is on loopback and ``$LAUNCHKIT_ROUTER_AUTOSTART`` is not ``0``: start
  the shared router there;
* otherwise wait for one, saying so once (or go on, for a node: Zenoh keeps trying).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

from launchkit.envvars import ROUTER_AUTOSTART, ROUTER_IDLE_TIMEOUT
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.own_process import not_subreaper
from launchkit.ros.endpoints import host_port, is_loopback
from launchkit.ros.port_owner import command_line
from launchkit.ros.router_access import router_answers
from launchkit.ros.rundir import locked, router_file

DEFAULT_IDLE_TIMEOUT = 300.0
START_TIMEOUT = 30.0  # for the background router to listen (a cold Python start under load)
LOCK_TIMEOUT = 60.0  # for another process that is starting it
WAIT_PERIOD = 0.1


@dataclass(frozen=True)
class SharedRouterState:
    """What the running shared router wrote about itself (its state file)."""

    pid: int
    endpoint: str
    idle_timeout: float
    log: str
    started: float  # seconds since the epoch

    @staticmethod
    def path(endpoint: str) -> Path:
        """The state file of the shared router at ``endpoint``."""
        return router_file(*host_port(endpoint), "json")

    @classmethod
    def read(cls, endpoint: str) -> SharedRouterState | None:
        """The state of the shared router at ``endpoint`` if its process still runs."""
        try:
            state = cls(**json.loads(cls.path(endpoint).read_text()))
        except (OSError, ValueError, TypeError):
            return None
        return state if _is_router_process(state.pid) else None

    def write(self) -> None:
        """Record this state (atomically: a reader never sees half of it)."""
        path = self.path(self.endpoint)
        partial = path.with_suffix(".partial")
        partial.write_text(json.dumps(asdict(self)))
        partial.replace(path)

    def remove(self) -> None:
        """Forget this state, unless another router has written its own since."""
        path = self.path(self.endpoint)
        try:
            if json.loads(path.read_text()).get("pid") == self.pid:
                path.unlink()
        except (OSError, ValueError):
            pass


def process_running(pid: int) -> bool:
    """Whether ``pid`` exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rpartition(")")[2].split()[0] != "Z"
    except OSError:
        pass
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return not Path("/proc").is_dir()  # /proc exists but had no such pid: gone


def _is_router_process(pid: int) -> bool:
    """Whether ``pid`` runs and is a shared router (not a process that reused its pid)."""
    if not process_running(pid):
        return False
    command = command_line(pid)
    return not command or "launchkit.ros.router_daemon" in command


def idle_timeout() -> float:
    """``$LAUNCHKIT_ROUTER_IDLE_TIMEOUT`` in seconds (0: never), else the default."""
    text = os.environ.get(ROUTER_IDLE_TIMEOUT, "")
    if not text:
        return DEFAULT_IDLE_TIMEOUT
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value >= 0:  # also refuses nan
        raise UserError(
            f"{ROUTER_IDLE_TIMEOUT}={text!r} is not a number of seconds",
            expected="a number >= 0 (0: never exit)",
        )
    return value


def autostart_enabled() -> bool:
    """Whether this process may start the shared router (``$LAUNCHKIT_ROUTER_AUTOSTART``)."""
    return os.environ.get(ROUTER_AUTOSTART, "1").strip().lower() not in ("0", "false", "no")


def start_shared_router(endpoint: str, idle: float | None = None) -> int | None:
    """Start the shared router at ``endpoint`` (loopback) in the background unless a router
    already listens there; the new router's pid, or None when one was there already."""
    host, port = host_port(endpoint)
    with locked(router_file(host, port, "lock"), LOCK_TIMEOUT, f"starting a router at {endpoint}"):
        if router_answers(endpoint):
            return None
        seconds = idle_timeout() if idle is None else idle
        router = [sys.executable, "-m", "launchkit.ros.router_daemon", endpoint]
        router += ["--idle-timeout", repr(seconds)]
        # sh starts the router in the background and exits at once: the router is then
        # nobody's child. It reports "ready PID" or an error on the pipe, then closes it.
        with not_subreaper():  # the router outlives a launch that starts it
            starter = subprocess.Popen(
                ["/bin/sh", "-c", '"$@" </dev/null & exit 0', "sh", *router],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                start_new_session=True,
                close_fds=True,
                cwd="/",
            )
            try:  # until the sh has exited, the router's parent to be is decided
                report, _ = starter.communicate(timeout=START_TIMEOUT)
            except subprocess.TimeoutExpired:
                os.killpg(starter.pid, signal.SIGKILL)  # the router is in the sh's group
                starter.wait()
                raise RuntimeLaunchError(
                    f"the shared ROS router at {endpoint} did not start in {START_TIMEOUT:.0f} s"
                ) from None
        text = report.decode(errors="replace").strip()
        if not text.startswith("ready "):
            raise RuntimeLaunchError(
                f"could not start the shared ROS router at {endpoint}: "
                + (text.removeprefix("error: ") or "it exited at once")
            )
        return int(text.split()[1])


def ensure_router(
    endpoint: str,
    *,
    autostart: bool | None = None,
    wait: bool = False,
    say: Callable[[str, str], None] | None = None,
) -> None:
    """Make sure a router this user may join answers at ``endpoint``: join one (returns at
    once), start the shared one (``autostart``; default ``$LAUNCHKIT_ROUTER_AUTOSTART``,
    loopback only), or, with ``wait``, wait for one as long as it takes. ``say(level,
    message)`` is told once of a start or a wait. Without ``wait`` a missing router is left
    to Zenoh's retries."""
    if router_answers(endpoint):
        return
    allowed = autostart_enabled() if autostart is None else autostart
    if allowed and is_loopback(endpoint):
        pid = start_shared_router(endpoint)
        if pid is not None and say is not None:
            say(
                "info",
                f"started the shared ROS router at {endpoint} in the background (pid {pid}; "
                "`launchkit router status` / `launchkit router stop`)",
            )
        return
    if not wait:
        return
    if say is not None:
        say(
            "warn",
            f"Unable to connect to a ROS router at {endpoint}: waiting for it (start "
            "`launchkit router` or a launch there, or point --router / LAUNCHKIT_ROUTER "
            "at a running one)",
        )
    while not router_answers(endpoint):
        time.sleep(WAIT_PERIOD)


def stop_shared_router(endpoint: str, timeout: float = 10.0) -> SharedRouterState | None:
    """Stop the shared router at ``endpoint`` (SIGTERM, SIGKILL after ``timeout`` seconds) and
    wait until it is gone; its state, or None when none runs there."""
    state = SharedRouterState.read(endpoint)
    if state is None:
        return None
    for signum, seconds in ((signal.SIGTERM, timeout), (signal.SIGKILL, timeout)):
        try:
            os.kill(state.pid, signum)
        except ProcessLookupError:
            break
        deadline = time.monotonic() + seconds
        while process_running(state.pid) and time.monotonic() < deadline:
            time.sleep(0.02)
        if not process_running(state.pid):
            break
    state.remove()  # it removes it itself, unless it had to be killed
    return state
