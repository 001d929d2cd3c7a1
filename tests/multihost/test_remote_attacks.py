"""The attacks on remote launching (issue #25, point 1), each by a graph member without the
agent key: an agent, a launcher and the attacker's Zenoh session on one loopback router.

The attacker captures what crosses the graph (events by subscribing, requests by declaring a
queryable on the agent's key: every querier's request reaches it) and plays it back elsewhere
or later. None of it may have an effect. Each negative is checked over a bounded window after
the attack was delivered to the router, with the real processes' state as the witness.
"""

from __future__ import annotations

import os
import random
import signal
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import zenoh
from netns import Proc

from launchkit.remote.keys import load_key
from launchkit.remote.sealing import REQUEST, refusal_of, seal
from launchkit.ros.session import client_config, close_session, open_session

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "ros"))
from launchkit.testing._isolation import free_loopback_port
from tests.support import sleepers

#: How long a forged message is given to (wrongly) take effect.
WINDOW = 2.0


@pytest.fixture
def lab(tmp_path: Path) -> Iterator[Lab]:
    """An agent key, a router port and the processes of one test (killed at the end)."""
    made = Lab(tmp_path)
    try:
        yield made
    finally:
        made.close()


class Lab:
    """Agents, launchers and an attacker session sharing one loopback router."""

    def __init__(self, tmp: Path) -> None:
        self.tmp = tmp
        self.endpoint = f"tcp/127.0.0.1:{free_loopback_port()}"
        self.marker = str(random.randrange(10**6, 10**7))  # `sleep MARKER`: our processes
        load_key(tmp / "agent.key", create=True)
        self.env = {
            "LAUNCHKIT_AGENT_KEY": str(tmp / "agent.key"),
            "ROS_LOG_DIR": str(tmp / "log"),
            "LAUNCHKIT_ROUTER_AUTOSTART": "1",
        }
        self.procs: list[Proc] = []
        self.attacker: Attacker | None = None
        # a router of its own: an agent restarted leaves it (and the attacker's link) alone
        self._start("router", "--router", self.endpoint).expect("listening at")

    def agent(self) -> Proc:
        """``launchkit agent --name hostb`` on the router."""
        proc = self._start("agent", "--name", "hostb", "--router", self.endpoint)
        proc.expect("agent hostb ready")
        return proc

    def launch(self, name: str, body: str, *args: str) -> Proc:
        """``launchkit run`` of a launch file whose ``body`` runs on hostb."""
        path = self.tmp / f"{name}.launch.xml"
        path.write_text(f'<launch><group machine="hostb">{body}</group></launch>\n')
        return self._start("run", str(path), "--router", self.endpoint, *args)

    def sleeper(self, name: str = "sleeper") -> str:
        """A remote process that says it is up, then sleeps."""
        command = f"sh -c 'echo {name}-up; exec sleep {self.marker}'"
        return f'<executable cmd="{command}" name="{name}" output="screen"/>'

    def sleepers(self) -> list[int]:
        """Pids of this test's sleeping processes still alive."""
        return sleepers(self.marker)

    def wait_sleepers(self, count: int, timeout: float = 10.0) -> list[int]:
        """The sleeping processes, once there are ``count`` (a sleeper says it is up just
        before it becomes ``sleep``)."""
        deadline = time.monotonic() + timeout
        while len(found := self.sleepers()) < count and time.monotonic() < deadline:
            time.sleep(0.02)
        return found

    def attack(self) -> Attacker:
        """The attacker's session (made once)."""
        if self.attacker is None:
            self.attacker = Attacker(self.endpoint)
        return self.attacker

    def _start(self, *args: str) -> Proc:
        proc = Proc([sys.executable, "-m", "launchkit", *args], self.env)
        self.procs.append(proc)
        return proc

    def close(self) -> None:
        """Stop every process (launchers first), then the attacker."""
        for proc in reversed(self.procs):
            if proc.proc.poll() is None:
                proc.stop()
            proc.close()
        if self.attacker is not None:
            self.attacker.close()
        for pid in self.sleepers():
            os.kill(pid, signal.SIGKILL)


class Attacker:
    """A graph member without the key: records events and requests, plays them back."""

    def __init__(self, endpoint: str) -> None:
        self.session = open_session(client_config(endpoint))
        self.events: list[tuple[str, bytes]] = []
        self.requests: list[bytes] = []
        self.answer: bytes | None = None  # what its queryable answers, if anything
        self._lock = threading.Lock()
        self._entities: list[Any] = [
            self.session.declare_subscriber("launchkit/launch/**", self._on_event),
            self.session.declare_queryable("launchkit/agent/hostb/requests", self._on_query),
        ]

    def _on_event(self, sample: zenoh.Sample) -> None:
        with self._lock:
            self.events.append((str(sample.key_expr), sample.payload.to_bytes()))

    def _on_query(self, query: zenoh.Query) -> None:
        if query.payload is not None:
            with self._lock:
                self.requests.append(query.payload.to_bytes())
        if self.answer is not None:
            query.reply(query.key_expr, self.answer)

    def event(self, part: str, kind: bytes, timeout: float = 30.0) -> tuple[str, bytes]:
        """The first captured event whose key contains ``part`` and payload ``kind``."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                for key, payload in self.events:
                    if part in key and kind in payload:
                        return key, payload
            time.sleep(0.02)
        raise AssertionError(f"no {kind!r} event of {part!r} captured within {timeout} s")

    def request(self, op: str, timeout: float = 30.0) -> bytes:
        """The first captured request for ``op``."""
        needle = f'\\"op\\":\\"{op}\\"'.encode()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                for payload in self.requests:
                    if needle in payload:
                        return payload
            time.sleep(0.02)
        raise AssertionError(f"no {op!r} request captured within {timeout} s")

    def ask(self, payload: bytes) -> list[bytes]:
        """Send ``payload`` to the agent's requests; every answer's bytes."""
        answers = []
        for reply in self.session.get(
            "launchkit/agent/hostb/requests",
            payload=payload,
            target=zenoh.QueryTarget.ALL,
            consolidation=zenoh.ConsolidationMode.NONE,
            timeout=5.0,
        ):
            if reply.ok is not None:
                answers.append(reply.ok.payload.to_bytes())
        return answers

    def ask_answered(self, payload: bytes, timeout: float = 15.0) -> list[bytes]:
        """:meth:`ask` again until the agent answers: a session that just joined, or an agent
        that just started, may not have its route to the agent's queryable yet."""
        deadline = time.monotonic() + timeout
        while not (answers := self.ask(payload)):
            assert time.monotonic() < deadline, f"the agent did not answer within {timeout} s"
        return answers

    def close(self) -> None:
        """Leave the graph."""
        for entity in self._entities:
            entity.undeclare()
        close_session(self.session)


def launch_of(key: str) -> str:
    """The launch id in an events key."""
    return key.split("/")[2]


def pid_of(line: str) -> int:
    """The pid in a ``process started with pid [N]`` line."""
    return int(line.rsplit("[", 1)[1].rstrip("]"))


def test_a_sealed_exit_means_nothing_under_another_process_or_launch(lab: Lab) -> None:
    lab.agent()
    attacker = lab.attack()
    quitter = '<executable cmd="sh -c \'echo bye; exit 3\'" name="quitter" output="screen"/>'
    first = lab.launch("first", quitter + lab.sleeper())
    sleeper_pid = pid_of(first.expect("[sleeper-2]: process started with pid"))
    wait_for_lines(first, "[quitter-1]: process has died", "[sleeper-2] sleeper-up")
    key, exit_event = attacker.event("/quitter-1/", b'\\"kind\\":\\"exit\\"')
    launch = launch_of(key)
    # the same sealed exit, for the other process of the same launch
    attacker.session.put(f"launchkit/launch/{launch}/events/sleeper-2/1", exit_event)
    # and for the process with that very label in another launch
    second = lab.launch("second", lab.sleeper("quitter"))
    second.expect("[quitter-1] quitter-up")
    other_key, _ = attacker.event("/quitter-1/", b"quitter-up")
    other = launch_of(other_key)
    assert other != launch
    attacker.session.put(f"launchkit/launch/{other}/events/quitter-1/1", exit_event)
    time.sleep(WINDOW)  # the window the forged exits had to take effect
    assert not any("[sleeper-2]: process has died" in line for line in _all(first))
    assert not any("process has died" in line for line in _all(second))
    assert sleeper_pid in lab.wait_sleepers(2)
    assert first.stop() == 0 and second.stop() == 0
    assert lab.sleepers() == []


def test_requests_captured_before_an_agent_restart_run_nothing(lab: Lab) -> None:
    agent = lab.agent()
    attacker = lab.attack()
    run = lab.launch("first", lab.sleeper())
    run.expect("[sleeper-1] sleeper-up")
    start = attacker.request("start")
    # the same run of the agent: a copy gets the first answer, nothing starts twice
    (again,) = attacker.ask_answered(start)
    assert b"restarted" not in again and refusal_of(again) is None
    time.sleep(WINDOW)
    assert len(lab.wait_sleepers(1)) == 1
    assert run.stop() == 0
    assert agent.stop() == 0
    assert lab.sleepers() == []
    agent = lab.agent()  # a new run of the agent
    (answer,) = attacker.ask_answered(start)
    assert b'\\"restarted\\":true' in answer, answer  # sealed, but for this request only
    time.sleep(WINDOW)
    assert lab.sleepers() == [], "a start request of the agent's earlier run was executed"
    assert not any("started sleeper" in line for line in _all(agent))
    # that sealed refusal, given by the attacker to every request of a new launch, fails
    # nothing: the launcher takes only the answer sealed for its own request
    attacker.answer = answer
    run = lab.launch("second", lab.sleeper())
    run.expect("[sleeper-1]: process started with pid")
    run.expect("[sleeper-1] sleeper-up")
    assert len(lab.wait_sleepers(1)) == 1
    assert run.stop() == 0


def test_a_forged_launcher_cannot_keep_a_launch_alive(lab: Lab) -> None:
    agent = lab.agent()
    attacker = lab.attack()
    run = lab.launch("first", lab.sleeper(), "--remote-grace", "1")
    run.expect("[sleeper-1] sleeper-up")
    alive = attacker.request("alive")
    launch = launch_of(attacker.event("/sleeper-1/", b"sleeper-up")[0])
    # the launcher token the agent once trusted, and the launcher's heartbeats played back
    token = attacker.session.liveliness().declare_token(f"launchkit/launch/{launch}/launcher")
    run.signal(signal.SIGKILL)
    stop = threading.Event()

    def replay() -> None:
        while not stop.wait(0.2):
            attacker.ask(alive)

    replayer = threading.Thread(target=replay)
    replayer.start()
    try:
        agent.expect(f"the launcher of launch {launch} is gone: stopping its processes")
        deadline = time.monotonic() + 15
        while lab.sleepers():
            assert time.monotonic() < deadline, "the launch's process outlived its launcher"
            time.sleep(0.05)
    finally:
        stop.set()
        replayer.join()
        token.undeclare()


def test_forged_agent_tokens_give_nothing_up(lab: Lab) -> None:
    lab.agent()
    attacker = lab.attack()
    run = lab.launch("first", lab.sleeper(), "--remote-grace", "1")
    pid = pid_of(run.expect("[sleeper-1]: process started with pid"))
    run.expect("[sleeper-1] sleeper-up")
    token = attacker.session.liveliness().declare_token("launchkit/agent/hostb/instance/forged")
    try:
        time.sleep(WINDOW)  # heartbeats go on meanwhile: the agent's sealed answers count
        assert not any("process has died" in line for line in _all(run))
        assert lab.wait_sleepers(1) == [pid]
    finally:
        token.undeclare()
    assert run.stop() == 0


def test_senders_without_the_key_get_nothing_signed(lab: Lab) -> None:
    agent = lab.agent()
    attacker = lab.attack()
    wrong_key = b"w" * 64
    forged = {"op": "start", "agent": "hostb", "instance": "", "launch": "x", "seq": 1}
    for payload in (b"garbage", seal(wrong_key, REQUEST, forged)):
        (answer,) = attacker.ask_answered(payload)
        assert refusal_of(answer) is not None and b"mac" not in answer, answer
    agent.expect("refused a request: not sealed with this agent key")


def wait_for_lines(proc: Proc, *texts: str, timeout: float = 30.0) -> None:
    """Wait until ``proc`` printed a line containing each of ``texts``, in any order."""
    deadline = time.monotonic() + timeout
    while missing := [t for t in texts if not any(t in line for line in _all(proc))]:
        assert time.monotonic() < deadline, f"never printed {missing}: {proc.seen[-20:]}"
        time.sleep(0.05)


def _all(proc: Proc) -> list[str]:
    """Every line ``proc`` printed so far."""
    proc.rest()
    return proc.seen
