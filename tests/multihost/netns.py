"""Hosts for multi-host tests: Linux network namespaces joined by a veth pair.

Each :class:`Hosts` makes two namespaces named after this process and a counter (so parallel
runs never collide), links them with a veth pair whose addresses exist only inside them, and
removes everything on :meth:`Hosts.close` (pytest finalizers) or, failing that, at exit.
Processes started in a namespace are ``ip netns exec NS ...`` (the same pid: ``ip`` execs).
"""

from __future__ import annotations

import atexit
import itertools
import os
import signal
import subprocess
import sys
from dataclasses import dataclass, field

from tests.suite_env import PRIVATE_DEFAULTS
from tests.support import OutputLines

_counter = itertools.count()
_alive: set[str] = set()


def netns_unavailable() -> str | None:
    """Why network namespaces cannot be made here (None when they can)."""
    if sys.platform != "linux":
        return "network namespaces are Linux only"
    if os.geteuid() != 0:
        return "making network namespaces needs root"
    probe = f"lkprobe{os.getpid()}"
    made = subprocess.run(["ip", "netns", "add", probe], capture_output=True, text=True)
    if made.returncode != 0:
        return f"`ip netns add` failed: {made.stderr.strip() or made.returncode}"
    subprocess.run(["ip", "netns", "del", probe], capture_output=True)
    return None


def host_environment(env: dict[str, str] | None = None) -> dict[str, str]:
    """The environment of a process on a host: the test's, less the private router, viewer
    port and ROS domain the suite gives the test process (a host is a machine of its own, with
    the defaults and ports of its own), plus ``env``."""
    inherited = {name: value for name, value in os.environ.items() if name not in PRIVATE_DEFAULTS}
    return {**inherited, **(env or {})}


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True)


class Proc:
    """A process in a namespace; its output lines (stdout and stderr together) read as they come."""

    def __init__(self, argv: list[str], env: dict[str, str] | None) -> None:
        self.argv = argv
        self.proc = subprocess.Popen(
            argv,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=host_environment(env),
            start_new_session=True,
        )
        assert self.proc.stdout is not None
        self.out = OutputLines(self.proc.stdout)

    @property
    def pid(self) -> int:
        """The process id (``ip netns exec`` execs the command: the same process)."""
        return self.proc.pid

    @property
    def seen(self) -> list[str]:
        """The lines taken so far (by :meth:`expect` and :meth:`rest`)."""
        return self.out.seen

    def expect(self, text: str, timeout: float = 30.0) -> str:
        """The next line containing ``text``; fails after ``timeout`` s naming what came."""
        return self.out.expect(
            text,
            timeout,
            lambda: (
                f"from {self.argv[4:]}; exit={self.proc.poll()}; last lines:\n"
                + "\n".join(self.seen[-30:])
            ),
        )

    def rest(self) -> list[str]:
        """The lines printed since the last one taken (taken now)."""
        return self.out.drain()

    def signal(self, signum: int) -> None:
        """Send ``signum`` to the process (not its group)."""
        if self.proc.poll() is None:
            os.kill(self.proc.pid, signum)

    def stop(self, timeout: float = 15.0) -> int:
        """SIGINT, then SIGKILL of its whole group after ``timeout`` s; the exit status."""
        self.signal(signal.SIGINT)
        try:
            self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()
        return self.proc.returncode

    def close(self) -> None:
        """Kill what is left and release the pipes."""
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self.proc.wait()
        self.out.join()
        for stream in (self.proc.stdin, self.proc.stdout):
            if stream is not None:
                stream.close()


@dataclass
class Host:
    """One namespace: its ``name``, its ``address`` on the link, its veth ``device``."""

    name: str
    address: str
    device: str
    procs: list[Proc] = field(default_factory=list)

    def start(self, *args: str, env: dict[str, str] | None = None) -> Proc:
        """Start ``python ARGS`` in this host (stopped and killed at the end of the test)."""
        proc = Proc(["ip", "netns", "exec", self.name, sys.executable, *args], env)
        self.procs.append(proc)
        return proc

    def launchkit(self, *args: str, env: dict[str, str] | None = None) -> Proc:
        """Start ``launchkit ARGS`` in this host."""
        return self.start("-m", "launchkit", *args, env=env)

    def run(
        self, *args: str, timeout: float = 60, env: dict[str, str] | None = None, check: bool = True
    ) -> str:
        """Run ``launchkit ARGS`` here to its end; its output (``check``: it must exit 0)."""
        done = subprocess.run(
            ["ip", "netns", "exec", self.name, sys.executable, "-m", "launchkit", *args],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=host_environment(env),
        )
        if check:
            assert done.returncode == 0, f"launchkit {args} exited {done.returncode}: {done.stderr}"
        return done.stdout

    def pids(self) -> list[int]:
        """Every process in the namespace."""
        out = subprocess.run(["ip", "netns", "pids", self.name], capture_output=True, text=True)
        return [int(pid) for pid in out.stdout.split()]

    def set_link(self, up: bool) -> None:
        """Bring this host's end of the link down or up (cutting or mending it)."""
        _ip("-n", self.name, "link", "set", self.device, "up" if up else "down")


class Hosts:
    """Two hosts, ``a`` (10.231.0.1) and ``b`` (10.231.0.2), on one link."""

    def __init__(self) -> None:
        tag = f"{os.getpid() % 100000}x{next(_counter)}"
        self.a = Host(f"lk{tag}a", "10.231.0.1", f"lk{tag}a")
        self.b = Host(f"lk{tag}b", "10.231.0.2", f"lk{tag}b")
        for host in (self.a, self.b):
            _ip("netns", "add", host.name)
            _alive.add(host.name)
            _ip("-n", host.name, "link", "set", "lo", "up")
        _ip("link", "add", self.a.device, "type", "veth", "peer", "name", self.b.device)
        for host in (self.a, self.b):
            _ip("link", "set", host.device, "netns", host.name)
            _ip("-n", host.name, "addr", "add", f"{host.address}/30", "dev", host.device)
            host.set_link(True)

    def close(self) -> None:
        """Stop every process started in the hosts, then remove the namespaces."""
        for host in (self.a, self.b):
            for proc in host.procs:
                proc.close()
        for host in (self.a, self.b):
            _remove(host.name)


def _remove(name: str) -> None:
    out = subprocess.run(["ip", "netns", "pids", name], capture_output=True, text=True)
    for pid in out.stdout.split():
        try:
            os.kill(int(pid), signal.SIGKILL)
        except ProcessLookupError:
            pass
    subprocess.run(["ip", "netns", "del", name], capture_output=True)
    _alive.discard(name)


@atexit.register
def _remove_leftovers() -> None:
    for name in list(_alive):
        _remove(name)
