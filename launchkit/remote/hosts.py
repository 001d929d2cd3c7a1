"""The launcher's side of launching on other hosts: one Zenoh session for the launch, the
agents it sees, the requests it sends them, and the events it routes to its remote processes.

The session opens with the first remote process (the launch's router is started first, as for
a node). The launcher's liveliness token tells agents it is alive; an agent that sees it gone
for the grace period stops the launch's processes by itself. Waits for an agent or a reply
block the supervisor's loop, so they end on SIGINT/SIGTERM at once: the signal still reaches
the loop through its wakeup pipe afterwards and shuts the launch down.
"""

from __future__ import annotations

import contextlib
import errno
import queue
import signal
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any
from urllib.parse import unquote

import zenoh

from launchkit.envvars import ROUTER
from launchkit.errors import LaunchkitError
from launchkit.remote.keys import load_key
from launchkit.remote.protocol import (
    ProtocolError,
    agent_requests,
    agent_tokens,
    encode_spec,
    events_of,
    launcher_token,
    new_id,
    parse_agent_token,
    request,
    seal,
    unseal,
)
from launchkit.remote.remote_process import RemoteProcess
from launchkit.ros.context import Context
from launchkit.runtime.signals import HANDLED_SIGNALS

if TYPE_CHECKING:
    from launchkit.description.launch_context import Runner
    from launchkit.description.process_spec import ProcessSpec
    from launchkit.runtime.network import NodeNetwork

REPLY_TIMEOUT = 15.0


class Interrupted(Exception):
    """A signal for the launcher arrived while waiting."""


def interruptible(wait: Callable[[float], bool], timeout: float) -> bool:
    """Call ``wait(slice)`` until it returns True or ``timeout`` passes (False); raise
    :class:`Interrupted` when a launcher signal arrives meanwhile (main thread only)."""
    hit = threading.Event()
    previous: dict[signal.Signals, Any] = {}
    if threading.current_thread() is threading.main_thread():
        for signum in HANDLED_SIGNALS:
            previous[signum] = signal.signal(signum, lambda *_: hit.set())
    try:
        deadline = time.monotonic() + timeout
        while not hit.is_set():
            if wait(0.05):
                return True
            if time.monotonic() > deadline:
                return False
        raise Interrupted
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


class RemoteHosts:
    """Every remote process of one launch, and the session that reaches their agents."""

    def __init__(
        self, network: NodeNetwork, key_path: Path | None, grace: float, agent_timeout: float
    ) -> None:
        self.launch = new_id()
        self.grace = grace
        self.agent_timeout = agent_timeout
        self._network = network
        self._key_path = key_path
        self._key = b""
        self._runner: Runner | None = None
        self._context: Context | None = None
        self._entities: list[Any] = []
        self._processes: dict[str, RemoteProcess] = {}
        self._agents: dict[str, str] = {}  # name -> instance seen now
        self._cond = threading.Condition()
        self._timers: dict[str, threading.Timer] = {}
        self._announced: set[str] = set()

    def bind(self, runner: Runner) -> None:
        """The launch's runner (for its router and its log lines)."""
        self._runner = runner

    def factory(self, spec: ProcessSpec, label: str, index: int) -> RemoteProcess:
        """The supervisor's process factory for specs with a ``machine``."""
        process = RemoteProcess(self, spec, label, index)
        self._processes[label] = process
        return process

    def _log(self, level: str, logger: str, message: str) -> None:
        if self._runner is not None:
            self._runner.log(level, logger, message)

    # -- the session ----------------------------------------------------------------------

    def _open(self) -> Any:
        if self._context is not None:
            return self._context.session
        assert self._runner is not None, "RemoteHosts.bind() was not called"
        self._key = load_key(self._key_path)
        endpoint = self._network.ensure(self._runner)[ROUTER]
        context = Context(router=endpoint, start_router=False)
        context.init([])
        session = context.session
        self._context = context
        self._entities = [
            session.liveliness().declare_subscriber(agent_tokens(), self._on_agent, history=True),
            session.declare_subscriber(events_of(self.launch), self._on_event),
            session.liveliness().declare_token(launcher_token(self.launch)),
        ]
        return session

    def close(self) -> None:
        """Leave the graph (the supervisor has stopped every process)."""
        for timer in self._timers.values():
            timer.cancel()
        for entity in reversed(self._entities):
            with contextlib.suppress(Exception):
                entity.undeclare()
        self._entities = []
        if self._context is not None:
            self._context.try_shutdown()
            self._context = None

    # -- agents ---------------------------------------------------------------------------

    def _on_agent(self, sample: zenoh.Sample) -> None:  # a Zenoh thread
        parsed = parse_agent_token(str(sample.key_expr))
        if parsed is None:
            return
        name, instance = parsed
        with self._cond:
            if sample.kind == zenoh.SampleKind.PUT:
                self._agents[name] = instance
                self._cond.notify_all()
            elif self._agents.get(name) == instance:
                del self._agents[name]
        for process in list(self._processes.values()):
            if process.machine != name or not process.instance or process.poll() is not None:
                continue
            if sample.kind == zenoh.SampleKind.PUT and process.instance != instance:
                process.lost(f"agent {name} restarted: its processes were stopped")
            elif sample.kind == zenoh.SampleKind.PUT:
                self._cancel(process.label)
            elif process.instance == instance:
                self._lose_later(process, name)

    def _lose_later(self, process: RemoteProcess, name: str) -> None:
        self._cancel(process.label)
        why = f"lost agent {name} for {self.grace:g} s: it stops this process by itself"
        timer = threading.Timer(self.grace, process.lost, (why,))
        timer.daemon = True
        self._timers[process.label] = timer
        timer.start()

    def _cancel(self, label: str) -> None:
        timer = self._timers.pop(label, None)
        if timer is not None:
            timer.cancel()

    def _wait_agent(self, name: str) -> str:
        def present(seconds: float) -> bool:
            with self._cond:
                return self._cond.wait_for(lambda: name in self._agents, seconds)

        if not present(0.0) and name not in self._announced:
            self._log(
                "INFO", "launch", f"waiting for agent {name} (`launchkit agent --name {name}`)"
            )
            self._announced.add(name)
        if not interruptible(present, self.agent_timeout):
            raise OSError(
                errno.EHOSTUNREACH,
                f"no agent {name} on the graph after {self.agent_timeout:g} s "
                f"(is `launchkit agent --name {name}` running, its router linked to this one?)",
            )
        with self._cond:
            return self._agents[name]

    # -- requests and events --------------------------------------------------------------

    def start(self, process: RemoteProcess) -> int:
        """Have ``process``'s agent start its new incarnation; its pid there."""
        try:
            session = self._open()
            instance = self._wait_agent(process.machine)
        except Interrupted:
            raise OSError(errno.EINTR, "interrupted while waiting for its agent") from None
        except LaunchkitError as error:
            raise OSError(errno.EPERM, error.message) from None
        message = request(
            "start",
            launch=self.launch,
            label=process.label,
            incarnation=process.incarnation,
            grace=self.grace,
            spec=encode_spec(process.spec),
        )
        try:
            reply = self._ask(session, process.machine, message)
        except Interrupted:
            raise OSError(errno.EINTR, "interrupted while its agent was starting it") from None
        if not reply.get("ok"):
            raise OSError(errno.EREMOTEIO, f"agent {process.machine}: {reply.get('error')}")
        process.instance = instance
        return int(reply["pid"])

    def _ask(self, session: Any, name: str, message: dict[str, Any]) -> dict[str, Any]:
        answers: queue.Queue[dict[str, Any]] = queue.Queue()

        def ask() -> None:
            for reply in session.get(
                agent_requests(name), payload=seal(self._key, message), timeout=REPLY_TIMEOUT
            ):
                try:
                    answers.put(unseal(self._key, reply.ok.payload.to_bytes()))
                except (ProtocolError, AttributeError, TypeError):
                    answers.put({"ok": False, "error": "an answer not sealed with the key"})
                return
            answers.put({"ok": False, "error": f"no answer in {REPLY_TIMEOUT:g} s"})

        threading.Thread(target=ask, daemon=True).start()
        got: list[dict[str, Any]] = []

        def answered(seconds: float) -> bool:
            with contextlib.suppress(queue.Empty):
                got.append(answers.get(timeout=seconds))
            return bool(got)

        interruptible(answered, REPLY_TIMEOUT + 1.0)
        return got[0] if got else {"ok": False, "error": "no answer"}

    def signal(self, process: RemoteProcess, signum: int) -> None:
        """Ask the agent to signal ``process`` (not waiting for its answer)."""
        if self._context is None or process.poll() is not None:
            return
        message = request(
            "signal",
            launch=self.launch,
            label=process.label,
            incarnation=process.incarnation,
            signum=int(signum),
        )
        session = self._context.session
        key, payload = agent_requests(process.machine), seal(self._key, message)
        threading.Thread(
            target=lambda: list(session.get(key, payload=payload, timeout=REPLY_TIMEOUT)),
            daemon=True,
        ).start()

    def _on_event(self, sample: zenoh.Sample) -> None:  # a Zenoh thread
        parts = str(sample.key_expr).split("/")
        if len(parts) != 6:
            return
        process = self._processes.get(unquote(parts[4]))
        try:
            event = unseal(self._key, sample.payload.to_bytes())
            incarnation = int(parts[5])
        except (ProtocolError, ValueError):
            return
        if process is not None:
            process.deliver(incarnation, event)
