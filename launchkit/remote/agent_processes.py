"""The processes an agent runs for launchers: started, read, signalled and reaped on the agent's
loop, each in a process group of its own under the agent's orphan guard.

The launcher's lifecycle decides what happens to them (:mod:`launchkit.remote.remote_process`);
the agent's own :class:`~launchkit.runtime.lifecycle.Lifecycle` of each process is used only
when the agent stops a launch by itself (its launcher is gone): the same SIGINT, SIGTERM,
SIGKILL ladder with the process's own timeouts.
"""

from __future__ import annotations

import os
import selectors
import signal
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from launchkit.description.process_spec import ProcessSpec
from launchkit.envvars import ROUTER, ROUTER_AUTOSTART, SUPERVISOR_SOCKET
from launchkit.ros.face import child_environment
from launchkit.runtime.lifecycle import SendSignal
from launchkit.runtime.process import ManagedProcess

#: publish(launch, label, incarnation, event)
Publish = Callable[[str, str, int, dict[str, Any]], None]
Key = tuple[str, str]  # (launch, label)


def build_spec(label: str, fields: Mapping[str, Any], scratch: Path, router: str) -> ProcessSpec:
    """The process to run here for a start request's ``spec``: this host's environment with
    the launch's changes, this host's router and Python, its generated files written here."""
    env = dict(os.environ)
    for name, value in dict(fields.get("env_changes") or {}).items():
        if value is None:
            env.pop(name, None)
        else:
            env[name] = str(value)
    if fields.get("domain") is not None:
        env["ROS_DOMAIN_ID"] = str(fields["domain"])
    env[ROUTER] = router
    env[ROUTER_AUTOSTART] = "0"
    env.pop(SUPERVISOR_SOCKET, None)  # the launcher's socket is on the launcher's host
    cmd = [str(part) for part in fields["cmd"]]
    if cmd and cmd[0] == fields.get("python"):
        cmd[0] = sys.executable
    for path, text in dict(fields.get("files") or {}).items():
        local = scratch / f"{label}-{Path(path).name}"
        local.write_text(str(text))
        cmd = [part.replace(path, str(local)) for part in cmd]
    env.update(child_environment(cmd, env))  # this host's face, unless the real rclpy is chosen
    cwd = fields.get("cwd")
    if cwd and not Path(cwd).is_dir():
        raise FileNotFoundError(2, f"no folder {cwd} on this host (the process's cwd)")
    return ProcessSpec(
        name=str(fields.get("name") or label),
        cmd=cmd,
        env=env,
        cwd=cwd or None,
        emulate_tty=bool(fields.get("emulate_tty")),
        sigterm_timeout=float(fields.get("sigterm_timeout", 5.0)),
        sigkill_timeout=float(fields.get("sigkill_timeout", 5.0)),
    )


class AgentProcess:
    """One incarnation of a launch's process on this host."""

    def __init__(
        self, launch: str, label: str, incarnation: int, spec: ProcessSpec, on_spawn: Any
    ) -> None:
        self.launch = launch
        self.label = label
        self.incarnation = incarnation
        self.managed = ManagedProcess(spec, label, 0, on_spawn)


class ProcessTable:
    """Every process this agent runs, registered with the agent loop's ``selector``."""

    def __init__(
        self,
        selector: selectors.BaseSelector,
        publish: Publish,
        on_spawn: Callable[[int], None],
        log: Callable[[str], None],
    ) -> None:
        self._selector = selector
        self._publish = publish
        self._on_spawn = on_spawn
        self._log = log
        self.processes: dict[Key, AgentProcess] = {}

    def of_launch(self, launch: str) -> list[AgentProcess]:
        """The running processes of ``launch``."""
        return [p for p in self.processes.values() if p.launch == launch]

    def start(self, launch: str, label: str, incarnation: int, spec: ProcessSpec) -> int:
        """Start ``spec`` as ``label``'s incarnation; its pid (``OSError`` if it cannot)."""
        old = self.processes.get((launch, label))
        if old is not None:  # a respawn before the old exit was read: it goes first
            old.managed.kill_leftovers()
            old.managed.reap()
            self._exited(old)
        process = AgentProcess(launch, label, incarnation, spec, self._on_spawn)
        process.managed.spawn()
        process.managed.lifecycle.started()
        self.processes[(launch, label)] = process
        managed = process.managed
        for fd in managed.streams:
            self._selector.register(fd, selectors.EVENT_READ, (self._read, process, fd))
        if managed.pidfd is not None:
            self._selector.register(managed.pidfd, selectors.EVENT_READ, (self._exited, process))
        assert managed.pid is not None
        return managed.pid

    def signal(self, launch: str, label: str, incarnation: int, signum: int) -> None:
        """Send ``signum`` to the process group of that incarnation (if it still runs)."""
        process = self.processes.get((launch, label))
        if process is not None and process.incarnation == incarnation:
            process.managed.signal_group(signum)

    def stop_launch(self, launch: str, now: float) -> None:
        """Begin stopping every process of ``launch`` (the first signal of each one's ladder)."""
        for process in self.of_launch(launch):
            effect = process.managed.lifecycle.stop(now)
            if effect is not None:
                self._send(process, effect)

    def stop_all(self, now: float) -> None:
        """Begin stopping every process."""
        for launch in {p.launch for p in self.processes.values()}:
            self.stop_launch(launch, now)

    def deadline(self) -> float | None:
        """When :meth:`due` has an escalation to make, if ever."""
        deadlines = [
            p.managed.lifecycle.deadline
            for p in self.processes.values()
            if p.managed.lifecycle.deadline is not None
        ]
        return min(deadlines) if deadlines else None

    def due(self, now: float) -> None:
        """Escalate the stops that took too long."""
        for process in list(self.processes.values()):
            effect = process.managed.lifecycle.due(now)
            if isinstance(effect, SendSignal):
                self._send(process, effect)

    def poll(self) -> None:
        """Look for exits of processes without a pidfd (kernels without pidfd_open)."""
        for process in list(self.processes.values()):
            if process.managed.pidfd is None and process.managed.poll() is not None:
                self._exited(process)

    def _send(self, process: AgentProcess, effect: SendSignal) -> None:
        name = signal.Signals(effect.signum).name
        self._log(f"{process.label} of launch {process.launch}: sending {name}")
        process.managed.signal_group(effect.signum)

    def _read(self, process: AgentProcess, fd: int) -> None:
        lines, eof = process.managed.read(fd)
        kind = process.managed.streams[fd].kind
        for line in lines:
            event = {"kind": "line", "stream": kind, "text": line}
            self._publish(process.launch, process.label, process.incarnation, event)
        if eof:
            self._selector.unregister(fd)
            process.managed.close_stream(fd)

    def _exited(self, process: AgentProcess) -> None:
        managed = process.managed
        code = managed.poll()
        if code is None:
            return
        if managed.pidfd is not None:
            self._selector.unregister(managed.pidfd)
            managed.close_pidfd()
        for fd in list(managed.streams):
            self._read(process, fd)
            if fd in managed.streams:
                self._selector.unregister(fd)
                managed.close_stream(fd)
        managed.kill_leftovers()  # nothing of a finished process stays behind on this host
        managed.lifecycle.exited(code, 0.0, respawn_allowed=False)
        if self.processes.get((process.launch, process.label)) is process:
            del self.processes[(process.launch, process.label)]
        event = {"kind": "exit", "code": code}
        self._publish(process.launch, process.label, process.incarnation, event)
