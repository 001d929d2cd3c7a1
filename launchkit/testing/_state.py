"""What the test process knows about a running launch, built from the launcher's events.

The reader thread applies events under :attr:`LaunchState.condition` and wakes every waiter;
the test's thread reads the state under the same condition.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class OutputLine:
    """One line a process wrote."""

    stream: str  # "stdout" or "stderr" (a pty, emulate_tty, is "stdout")
    text: str


@dataclass
class ProcessRecord:
    """One process of the launch (all its incarnations when it respawns)."""

    label: str  # "talker-1": unique within the launch
    name: str  # "talker": the name attribute or the executable's name
    node: str | None  # the ROS node name a <node> sets, if any
    cmd: list[str]
    respawn: bool
    escalation: float  # sigterm_timeout + sigkill_timeout: the launcher's worst stop time
    required: bool = False  # on_exit="shutdown": its end ends the launch
    pids: list[int] = field(default_factory=list)
    running: bool = False
    returncode: int | None = None
    exited_while_stopping: bool = False  # the launch was shutting down when it exited
    stop_requested: bool = False  # the launcher is stopping this process alone
    noted: bool = False  # the test took note of its exit (wait_exit, returncode)
    lines: list[OutputLine] = field(default_factory=list)

    @property
    def pid(self) -> int | None:
        """The pid of the latest incarnation."""
        return self.pids[-1] if self.pids else None

    def matches(self, query: str) -> bool:
        """Whether ``query`` names this process (label, name or ROS node name)."""
        return query in (self.label, self.name, self.node)

    def died_unexpectedly(self) -> bool:
        """A non-zero exit (or a signal) nobody asked for: not while the launch or the launcher
        was stopping it, and not of a respawning process (those may die). Whether the test took
        note of it is :attr:`noted`."""
        return (
            not self.running
            and self.returncode not in (None, 0)
            and not self.exited_while_stopping
            and not self.respawn
        )


class LaunchState:
    """The launch as seen through its events; guarded by :attr:`condition`."""

    def __init__(self) -> None:
        self.condition = threading.Condition()
        self.processes: dict[str, ProcessRecord] = {}
        self.ready = False
        self.failure: str | None = None  # the launcher's message when it failed before ready
        self.errors: list[str] = []  # errors while running
        self.shutdown_reason: str | None = None
        self.stopping = False  # the test asked the launch to stop
        self.channel_closed = False
        self.launcher_returncode: int | None = None

    def apply(self, event: dict[str, Any]) -> None:
        """Take in one event from the launcher and wake the waiters."""
        with self.condition:
            try:
                self._apply(event)
            except (KeyError, TypeError, ValueError):
                pass  # not an event this version understands; keep following the launch
            self.condition.notify_all()

    def _apply(self, event: dict[str, Any]) -> None:
        kind = event.get("event")
        if kind == "output":
            record = self.processes.get(str(event["process"]))
            if record is not None:
                record.lines.append(OutputLine(str(event["stream"]), str(event["text"])))
        elif kind == "started":
            label = str(event["process"])
            record = self.processes.get(label)
            if record is None:
                record = ProcessRecord(
                    label=label,
                    name=str(event["name"]),
                    node=event.get("node"),
                    cmd=[str(word) for word in event["cmd"]],
                    respawn=bool(event.get("respawn")),
                    required=bool(event.get("required")),
                    escalation=float(event.get("sigterm_timeout", 5.0))
                    + float(event.get("sigkill_timeout", 5.0)),
                )
                self.processes[label] = record
            record.pids.append(int(event["pid"]))
            record.running = True
            record.returncode = None
            record.noted = False
            record.stop_requested = False
        elif kind == "exited":
            record = self.processes.get(str(event["process"]))
            if record is not None:
                record.running = False
                record.returncode = int(event["returncode"])
                record.exited_while_stopping = (
                    self.stopping or self.shutdown_reason is not None or record.stop_requested
                )
        elif kind == "stopping":
            record = self.processes.get(str(event["process"]))
            if record is not None:
                record.stop_requested = True
        elif kind == "ready":
            self.ready = True
        elif kind == "failed":
            self.failure = str(event["message"])
        elif kind == "error":
            self.errors.append(str(event["message"]))
        elif kind == "shutdown":
            self.shutdown_reason = str(event["reason"])

    def close_channel(self) -> None:
        """The launcher closed its end of the channel (it is exiting)."""
        with self.condition:
            self.channel_closed = True
            self.condition.notify_all()

    def launcher_exited(self, returncode: int) -> None:
        """The launcher process has exited with ``returncode``."""
        with self.condition:
            self.launcher_returncode = returncode
            self.channel_closed = True
            self.condition.notify_all()

    def all_pids(self) -> list[int]:
        """Every pid the launch ever reported (each is also its own process group)."""
        return [pid for record in self.processes.values() for pid in record.pids]

    def find(self, query: str) -> list[ProcessRecord]:
        """The processes ``query`` names."""
        return [record for record in self.processes.values() if record.matches(query)]
