"""The launcher's side of launching on other hosts: one Zenoh session for the launch, the
agents it uses, the sealed requests it sends them, and the events it routes to its remote
processes.

The session opens with the first remote process (the launch's router is started first, as for
a node). An agent's liveliness token only says where to look: the agent's run (its
``instance``) is learnt from its sealed answer to a ``hello``, and every request is bound to it
(:mod:`launchkit.remote.sealing`). A heartbeat thread tells each agent in use that the launcher
is alive (a sealed ``alive`` request); the answers tell the launcher the agent is, and whether
it restarted meanwhile. Waits for an agent or a reply block the supervisor's loop, so they end
on SIGINT/SIGTERM at once: the signal still reaches the loop through its wakeup pipe afterwards
and shuts the launch down.
"""

from __future__ import annotations

import contextlib
import errno
import itertools
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
    agent_requests,
    agent_tokens,
    encode_spec,
    events_of,
    heartbeat_period,
    new_id,
    parse_agent_token,
)
from launchkit.remote.remote_process import RemoteProcess
from launchkit.remote.sealing import (
    EVENT,
    REPLY,
    REQUEST,
    ProtocolError,
    refusal_of,
    seal,
    unseal,
)
from launchkit.ros.context import Context
from launchkit.runtime.signals import HANDLED_SIGNALS

if TYPE_CHECKING:
    from launchkit.description.launch_context import Runner
    from launchkit.description.process_spec import ProcessSpec
    from launchkit.runtime.network import NodeNetwork

REPLY_TIMEOUT = 15.0
HELLO_TIMEOUT = 2.0  # an agent that answers at all answers a hello at once


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
        self._cond = threading.Condition()
        self._hinted: set[str] = set()  # agents whose token was seen (unsealed: a hint)
        self._instances: dict[str, str] = {}  # agent -> its run, from a sealed answer
        self._heard: dict[str, float] = {}  # agent -> when it last answered (monotonic)
        self._seq = itertools.count(1)
        self._stop = threading.Event()
        self._heartbeat: threading.Thread | None = None
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
        ]
        self._heartbeat = threading.Thread(
            target=self._beat, name="launchkit-remote-heartbeat", daemon=True
        )
        self._heartbeat.start()
        return session

    def close(self) -> None:
        """Leave the graph (the supervisor has stopped every process)."""
        self._stop.set()
        if self._heartbeat is not None:
            self._heartbeat.join(REPLY_TIMEOUT)
            self._heartbeat = None
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
        if parsed is not None and sample.kind == zenoh.SampleKind.PUT:
            with self._cond:
                self._hinted.add(parsed[0])
                self._cond.notify_all()

    def _wait_agent(self, name: str) -> str:
        """The run of agent ``name``, from its sealed answer to a hello (waiting for it to
        appear, at most the agent timeout)."""
        with self._cond:
            if name in self._instances:
                return self._instances[name]
        deadline = time.monotonic() + self.agent_timeout
        last_error = ""

        def answered(seconds: float) -> bool:
            nonlocal last_error
            with self._cond:
                if not self._cond.wait_for(lambda: name in self._hinted, seconds):
                    return False
            remaining = deadline - time.monotonic()
            reply = self._ask(name, "", "hello", max(0.1, min(HELLO_TIMEOUT, remaining)))
            if reply.get("ok"):
                return True
            last_error = str(reply.get("error", ""))
            return False

        if not answered(0.0) and name not in self._announced:
            self._log(
                "INFO", "launch", f"waiting for agent {name} (`launchkit agent --name {name}`)"
            )
            self._announced.add(name)
        if not interruptible(answered, self.agent_timeout):
            why = f" (its answer: {last_error})" if last_error else ""
            raise OSError(
                errno.EHOSTUNREACH,
                f"no agent {name} on the graph after {self.agent_timeout:g} s{why} "
                f"(is `launchkit agent --name {name}` running, its router linked to this one?)",
            )
        with self._cond:
            return self._instances[name]

    # -- requests and events --------------------------------------------------------------

    def start(self, process: RemoteProcess) -> int:
        """Have ``process``'s agent start its new incarnation; its pid there."""
        name = process.machine
        try:
            self._open()
            for _attempt in range(2):  # a second time if the agent turns out to have restarted
                process.instance = self._wait_agent(name)  # before any event can arrive
                reply = interruptible_ask(
                    lambda: self._ask(
                        name,
                        process.instance,
                        "start",
                        REPLY_TIMEOUT,
                        label=process.label,
                        incarnation=process.incarnation,
                        grace=self.grace,
                        spec=encode_spec(process.spec),
                    )
                )
                if not reply.get("restarted"):
                    break
        except Interrupted:
            raise OSError(errno.EINTR, "interrupted while its agent was starting it") from None
        except LaunchkitError as error:
            raise OSError(errno.EPERM, error.message) from None
        if not reply.get("ok"):
            raise OSError(errno.EREMOTEIO, f"agent {name}: {reply.get('error')}")
        return int(reply["pid"])

    def _ask(
        self, name: str, instance: str, op: str, timeout: float, **fields: Any
    ) -> dict[str, Any]:
        """Send a sealed request to agent ``name``'s run ``instance``; its sealed answer, or
        ``{"ok": false, "error": ...}``. Every agent-side queryable gets the request (a
        stranger's cannot keep it from the agent); answers not sealed for this very request
        are ignored."""
        if self._context is None:
            return {"ok": False, "error": "not connected"}
        seq = next(self._seq)
        message = {
            "op": op, "agent": name, "instance": instance, "launch": self.launch, "seq": seq,
            **fields,
        }  # fmt: skip
        refusal = None
        replies = self._context.session.get(
            agent_requests(name),
            payload=seal(self._key, REQUEST, message),
            target=zenoh.QueryTarget.ALL,
            consolidation=zenoh.ConsolidationMode.NONE,
            timeout=timeout,
        )
        for reply in replies:
            data = _reply_bytes(reply)
            try:
                answer = unseal(self._key, REPLY, data)
            except ProtocolError:
                refusal = refusal or refusal_of(data)
                continue
            if answer.get("launch") != self.launch or answer.get("seq") != seq:
                continue  # an answer to another request (a replay)
            if answer.get("agent") != name:
                continue
            self._heard_from(name, str(answer.get("instance", "")))
            return answer
        if refusal is not None:
            return {"ok": False, "error": f"refused the request: {refusal}"}
        return {"ok": False, "error": f"no answer in {timeout:g} s"}

    def _heard_from(self, name: str, instance: str) -> None:
        """A sealed answer of agent ``name``'s run ``instance`` arrived."""
        with self._cond:
            previous = self._instances.get(name)
            self._instances[name] = instance
            self._heard[name] = time.monotonic()
        if previous is not None and previous != instance:
            for process in self._of_agent(name):
                if process.instance != instance:
                    process.lost(f"agent {name} restarted: its processes were stopped")

    def _of_agent(self, name: str) -> list[RemoteProcess]:
        return [
            p
            for p in list(self._processes.values())
            if p.machine == name and p.instance and p.poll() is None
        ]

    def signal(self, process: RemoteProcess, signum: int) -> None:
        """Ask the agent to signal ``process`` (not waiting for its answer)."""
        if self._context is None or process.poll() is not None:
            return
        threading.Thread(
            target=self._ask,
            args=(process.machine, process.instance, "signal", REPLY_TIMEOUT),
            kwargs={
                "label": process.label,
                "incarnation": process.incarnation,
                "signum": int(signum),
            },
            daemon=True,
        ).start()

    def _beat(self) -> None:
        """Tell every agent in use that the launcher is alive; give up the processes of an
        agent that has not answered for the grace period."""
        period = heartbeat_period(self.grace)
        while not self._stop.wait(period):
            with self._cond:
                agents = dict(self._instances)
            for name, instance in agents.items():
                self._ask(name, instance, "alive", max(period, 1.0), grace=self.grace)
                with self._cond:
                    silent = time.monotonic() - self._heard.get(name, 0.0)
                if silent < self.grace:
                    continue
                for process in self._of_agent(name):
                    process.lost(
                        f"lost agent {name} for {self.grace:g} s: it stops this process by itself"
                    )

    def _on_event(self, sample: zenoh.Sample) -> None:  # a Zenoh thread
        parts = str(sample.key_expr).split("/")
        if len(parts) != 6:
            return
        label = unquote(parts[4])
        process = self._processes.get(label)
        try:
            event = unseal(self._key, EVENT, sample.payload.to_bytes())
            incarnation = int(parts[5])
        except (ProtocolError, ValueError):
            return
        if process is None:
            return
        bound = (event.get("launch"), event.get("label"), event.get("incarnation"))
        if bound != (self.launch, label, incarnation) or event.get("agent") != process.machine:
            return  # sealed, but for another launch, process or incarnation
        process.deliver(str(event.get("instance")), incarnation, event)


def interruptible_ask(ask: Callable[[], dict[str, Any]]) -> dict[str, Any]:
    """``ask()`` in a thread of its own; its answer, or :class:`Interrupted` on a launcher
    signal meanwhile."""
    answers: queue.Queue[dict[str, Any]] = queue.Queue()
    threading.Thread(target=lambda: answers.put(ask()), daemon=True).start()
    got: list[dict[str, Any]] = []

    def answered(seconds: float) -> bool:
        with contextlib.suppress(queue.Empty):
            got.append(answers.get(timeout=seconds))
        return bool(got)

    interruptible(answered, REPLY_TIMEOUT + 1.0)
    return got[0] if got else {"ok": False, "error": "no answer"}


def _reply_bytes(reply: Any) -> bytes:
    try:
        return bytes(reply.ok.payload.to_bytes())
    except (AttributeError, TypeError):
        return b""
