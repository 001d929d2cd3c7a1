"""``launchkit agent``: runs a host's share of launches started elsewhere.

The agent is a node on the graph (``/launchkit/agents/NAME`` in ``launchkit node list``) with a
liveliness token of its own run, and answers sealed requests to start and signal processes
(:mod:`launchkit.remote.sealing`: each executed once per run of the agent, whoever replays it).
Everything happens on one loop thread: Zenoh's threads hand requests over through a queue, and
the loop also reads the processes' output and exits (:mod:`launchkit.remote.agent_processes`).
A launch whose launcher has not said it is alive (a sealed ``alive`` request, every second or
so) for the grace period (the launcher was killed, or the link is cut) has its processes
stopped; the orphan guard kills every group the agent started should the agent itself die.
"""

from __future__ import annotations

import contextlib
import os
import queue
import re
import selectors
import shutil
import signal
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import zenoh

from launchkit.errors import LaunchkitError
from launchkit.remote.agent_processes import ProcessTable, build_spec
from launchkit.remote.protocol import (
    agent_requests,
    agent_token,
    events_key,
    heartbeat_period,
    new_id,
    silence_limit,
)
from launchkit.remote.sealing import (
    EVENT,
    REPLY,
    REQUEST,
    ProtocolError,
    ReplayGuard,
    seal,
    unseal,
    unsealed_refusal,
)
from launchkit.ros.context import Context
from launchkit.ros.node import Node
from launchkit.runtime.orphan_guard import OrphanGuard
from launchkit.runtime.process_io import POLL_INTERVAL

Say = Callable[[str, str], None]  # (level, message)
REPLY_TIMEOUT = 10.0
#: What a launcher may send a process: the stop ladder's signals.
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGKILL)


@dataclass
class LaunchWatch:
    """What the agent knows of one launch's launcher: when it last spoke (a sealed request)."""

    grace: float
    last_heard: float
    lost: bool = False
    stopping: bool = False

    @property
    def deadline(self) -> float:
        """When the launch's processes are stopped unless the launcher speaks again."""
        return self.last_heard + silence_limit(self.grace)

    @property
    def lost_at(self) -> float:
        """When the launcher counts as lost (three heartbeats missed)."""
        return self.last_heard + 3 * heartbeat_period(self.grace)


def node_name(name: str) -> str:
    """The agent's ROS node name for agent ``name``."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", name)
    return text if text[:1].isalpha() or text[:1] == "_" else f"n{text}"


class Agent:
    """One agent: its session, its process table, its loop (:meth:`run`)."""

    def __init__(self, name: str, key: bytes, router: str, say: Say) -> None:
        self.name = name
        self.key = key
        self.router = router
        self.instance = new_id()
        self._say = say
        self._selector = selectors.DefaultSelector()
        self._wake_r, self._wake_w = os.pipe()
        os.set_blocking(self._wake_r, False)
        os.set_blocking(self._wake_w, False)
        self._selector.register(self._wake_r, selectors.EVENT_READ, (self._drain,))
        self._jobs: queue.Queue[Callable[[], None]] = queue.Queue()
        self._guard = OrphanGuard()
        self._scratch = Path(tempfile.mkdtemp(prefix="launchkit-agent-"))
        self._guard.remove_on_death(str(self._scratch))
        self.table = ProcessTable(self._selector, self._publish, self._guard.watch, self._info)
        self.launches: dict[str, LaunchWatch] = {}
        self._replays = ReplayGuard()
        self._event_seq: dict[tuple[str, str, int], int] = {}
        self._context: Context | None = None
        self._node: Node | None = None
        self._entities: list[Any] = []

    # -- the graph ------------------------------------------------------------------------

    def open(self) -> None:
        """Join the graph: the node, the token, the request queryable, the launcher watch."""
        context = Context(router=self.router, start_router=False)
        context.init([])
        self._context = context
        self._node = Node(
            node_name(self.name),
            namespace="/launchkit/agents",
            context=context,
            start_parameter_services=False,
            enable_rosout=False,
        )
        session = context.session
        self._entities = [
            session.declare_queryable(agent_requests(self.name), self._on_query),
            session.liveliness().declare_token(agent_token(self.name, self.instance)),
        ]

    def _info(self, message: str) -> None:
        self._say("info", message)

    def _submit(self, job: Callable[[], None]) -> None:
        self._jobs.put(job)
        with contextlib.suppress(BlockingIOError):
            os.write(self._wake_w, b"!")

    def _drain(self) -> None:
        with contextlib.suppress(BlockingIOError):
            os.read(self._wake_r, 4096)
        while True:
            try:
                job = self._jobs.get_nowait()
            except queue.Empty:
                return
            job()

    def _on_query(self, query: zenoh.Query) -> None:  # a Zenoh thread
        try:
            payload = query.payload.to_bytes() if query.payload is not None else b""
            message = unseal(self.key, REQUEST, payload)
            if message.get("agent") != self.name:
                raise ProtocolError(f"a request for agent {message.get('agent')!r}")
        except ProtocolError as error:
            self._say("warn", f"refused a request: {error}")
            query.reply(query.key_expr, unsealed_refusal(str(error)))
            return
        answers: queue.Queue[dict[str, Any]] = queue.Queue()
        self._submit(lambda: answers.put(self._answer(message)))
        try:
            answer = answers.get(timeout=REPLY_TIMEOUT)
        except queue.Empty:
            answer = {"ok": False, "error": f"agent {self.name} did not answer in time"}
        bound = {
            key: message.get(key) for key in ("launch", "seq", "agent")
        }  # ties the answer to its request
        query.reply(query.key_expr, seal(self.key, REPLY, {**answer, **bound}))

    def _publish(self, launch: str, label: str, incarnation: int, event: dict[str, Any]) -> None:
        run = (launch, label, incarnation)
        seq = self._event_seq.get(run, 0) + 1
        if event.get("kind") == "exit":
            self._event_seq.pop(run, None)
        else:
            self._event_seq[run] = seq
        if self._context is not None:
            sealed = {
                **event,
                "agent": self.name,
                "instance": self.instance,
                "launch": launch,
                "label": label,
                "incarnation": incarnation,
                "seq": seq,
            }
            key = events_key(launch, label, incarnation)
            self._context.session.put(key, seal(self.key, EVENT, sealed))

    # -- on the loop ----------------------------------------------------------------------

    def _answer(self, message: dict[str, Any]) -> dict[str, Any]:
        """The answer to an authentic request: executed once per run of the agent, a copy
        gets the first answer again; ``instance`` says which run answered."""
        op, launch = message.get("op"), str(message.get("launch"))
        mine = {"instance": self.instance}
        if op != "hello" and message.get("instance") != self.instance:
            return {"ok": False, "restarted": True, "error": "agent restarted", **mine}
        now = time.monotonic()
        try:
            seq = int(message.get("seq", 0))
            answer = self._replays.answer_of(launch, seq, now)
        except (ProtocolError, TypeError, ValueError) as error:
            self._say("warn", f"refused a request: {error}")
            return {"ok": False, "error": str(error), **mine}
        if answer is None:
            answer = {**self._handle(message, now), **mine}
            self._replays.remember(launch, seq, answer, now)
        return answer

    def _handle(self, message: dict[str, Any], now: float) -> dict[str, Any]:
        op = message.get("op")
        launch, label = str(message.get("launch")), str(message.get("label"))
        if op == "hello":
            return {"ok": True}
        if op not in ("start", "signal", "alive"):
            return {"ok": False, "error": f"unknown request {op!r}"}
        try:
            grace = float(message.get("grace", 10.0))
            incarnation = int(message.get("incarnation", 0))
            signum = int(message.get("signum", 0))
        except (TypeError, ValueError) as error:
            return {"ok": False, "error": f"bad request: {error}"}
        watch = self.launches.get(launch)
        if watch is None:
            watch = self.launches[launch] = LaunchWatch(grace, now)
        elif not watch.stopping:
            self._heard(launch, watch, now)
        if op == "alive":
            watch.grace = grace
            return {"ok": True}
        if op == "signal":
            if signum not in STOP_SIGNALS:
                return {"ok": False, "error": f"signal {signum} is not one of the stop ladder"}
            self.table.signal(launch, label, incarnation, signum)
            return {"ok": True}
        watch.grace = grace
        if watch.stopping:
            return {"ok": False, "error": "its launcher was lost: this launch is stopping here"}
        fields = message.get("spec") or {}
        try:
            spec = build_spec(label, fields, self._scratch, self.router)
            pid = self.table.start(launch, label, incarnation, spec)
        except OSError as error:
            program = (fields.get("cmd") or ["?"])[0]
            return {"ok": False, "error": f"{error.strerror or error}: '{program}'"}
        except (LaunchkitError, KeyError, TypeError, ValueError) as error:
            return {"ok": False, "error": f"bad start request: {error}"}
        self._info(f"started {label} of launch {launch} (pid {pid})")
        return {"ok": True, "pid": pid}

    def _heard(self, launch: str, watch: LaunchWatch, now: float) -> None:
        if watch.lost and self.table.of_launch(launch):
            self._info(f"the launcher of launch {launch} is back")
        watch.lost = False
        watch.last_heard = now

    def _check_launches(self, now: float) -> None:
        for launch, watch in list(self.launches.items()):
            running = self.table.of_launch(launch)
            if running and not watch.lost and not watch.stopping and now >= watch.lost_at:
                watch.lost = True
                self._say(
                    "warn",
                    f"lost the launcher of launch {launch}: stopping its processes in "
                    f"{max(0.0, watch.deadline - now):g} s unless it comes back",
                )
            if running and not watch.stopping and now >= watch.deadline:
                self._say(
                    "warn", f"the launcher of launch {launch} is gone: stopping its processes"
                )
                watch.stopping = True
                self.table.stop_launch(launch, now)
            if not running and now >= watch.deadline:
                del self.launches[launch]  # its requests are refused by the replay guard

    def _timeout(self, now: float) -> float:
        deadlines = [self.table.deadline()]
        for launch, watch in self.launches.items():
            if not watch.stopping and self.table.of_launch(launch):
                deadlines.append(watch.deadline if watch.lost else watch.lost_at)
        due = [d for d in deadlines if d is not None]
        timeout = max(0.0, min(due) - now) if due else 1.0
        return min(timeout, POLL_INTERVAL if self._needs_polling() else 1.0)

    def _needs_polling(self) -> bool:
        return any(p.managed.pidfd is None for p in self.table.processes.values())

    def run(self, stop: threading.Event) -> None:
        """Serve until ``stop`` is set, then stop every process (a second ``stop`` after
        :meth:`escalate` kills them at once) and return when none is left."""
        stopping = False
        while True:
            now = time.monotonic()
            if stop.is_set() and not stopping:
                stopping = True
                self.table.stop_all(now)
            if stopping and not self.table.processes:
                return
            for key, _ in self._selector.select(self._timeout(now)):
                if self._selector.get_map().get(key.fd) is not key:
                    continue
                function, *args = key.data
                function(*args)
            self.table.poll()
            now = time.monotonic()
            self.table.due(now)
            self._check_launches(now)

    def escalate(self) -> None:
        """Kill every process now (the user insists)."""
        for process in list(self.table.processes.values()):
            process.managed.kill_leftovers()

    def wake(self) -> None:
        """Make the loop look at its stop flag (safe from a signal handler)."""
        with contextlib.suppress(OSError):
            os.write(self._wake_w, b"!")

    def close(self) -> None:
        """Leave the graph and release everything (every process is gone by now)."""
        for entity in reversed(self._entities):
            with contextlib.suppress(Exception):
                entity.undeclare()
        self._entities = []
        if self._node is not None:
            self._node.destroy_node()
            self._node = None
        if self._context is not None:
            self._context.try_shutdown()
            self._context = None
        self._guard.dismiss()
        shutil.rmtree(self._scratch, ignore_errors=True)
        self._selector.close()
        for fd in (self._wake_r, self._wake_w):
            os.close(fd)
