"""Launching on other hosts, piece by piece and without a network: the sealed protocol, the
agent key, the process an agent builds from a request, ``<group machine>``, and a remote
process supervised by the real supervisor through a stand-in agent."""

from __future__ import annotations

import io
import os
import signal
import stat
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from launchkit import api
from launchkit.description.process_spec import ProcessSpec
from launchkit.envvars import ROUTER, SUPERVISOR_SOCKET
from launchkit.errors import LaunchkitError
from launchkit.remote import remote_process
from launchkit.remote.agent_processes import build_spec
from launchkit.remote.keys import AgentKeyError, load_key
from launchkit.remote.launch import RemoteLaunch
from launchkit.remote.protocol import encode_spec
from launchkit.remote.remote_process import LOST, RemoteProcess
from launchkit.remote.sealing import (
    EVENT,
    REPLY,
    REQUEST,
    WINDOW,
    ProtocolError,
    ReplayGuard,
    refusal_of,
    seal,
    unseal,
    unsealed_refusal,
)

KEY = b"k" * 64


def test_messages_are_sealed_with_the_key_for_one_direction() -> None:
    message = {"op": "start", "launch": "l1", "seq": 1, "label": "talker-1"}
    opened = unseal(KEY, REQUEST, seal(KEY, REQUEST, message))
    assert opened == {**message, "v": 1, "dir": REQUEST}
    with pytest.raises(ProtocolError, match="not sealed with this agent key"):
        unseal(b"x" * 64, REQUEST, seal(KEY, REQUEST, message))
    tampered = seal(KEY, REQUEST, message).replace(b"talker-1", b"talker-2")
    with pytest.raises(ProtocolError):
        unseal(KEY, REQUEST, tampered)
    for other in (REPLY, EVENT):  # a sealed reply or event is never a request
        with pytest.raises(ProtocolError, match="where a 'request' belongs"):
            unseal(KEY, REQUEST, seal(KEY, other, message))
    refusal = unsealed_refusal("not sealed with this agent key")
    assert refusal_of(refusal) == "not sealed with this agent key"
    with pytest.raises(ProtocolError, match="malformed"):
        unseal(KEY, REPLY, refusal)


def test_an_agent_executes_each_request_once_and_forgets_nothing_recent() -> None:
    guard = ReplayGuard()
    assert guard.answer_of("l1", 5, now=0.0) is None
    guard.remember("l1", 5, {"ok": True, "pid": 7}, now=0.0)
    assert guard.answer_of("l1", 5, now=1.0) == {"ok": True, "pid": 7}  # a copy: same answer
    assert guard.answer_of("l1", 3, now=1.0) is None  # overtaken on the way: still new
    assert guard.answer_of("l2", 5, now=1.0) is None  # another launch counts on its own
    guard.remember("l1", 5 + WINDOW, {"ok": True}, now=1.0)
    with pytest.raises(ProtocolError, match="too old"):
        guard.answer_of("l1", 5, now=2.0)
    with pytest.raises(ProtocolError, match="without its number"):
        guard.answer_of("l1", 0, now=2.0)
    with pytest.raises(ProtocolError, match="ended here"):
        guard.answer_of("l1", 6 + WINDOW, now=10_000.0)  # silent for long: the launch ended


def test_the_agent_key_is_made_private_and_checked(tmp_path: Path) -> None:
    path = tmp_path / "conf" / "agent.key"
    with pytest.raises(AgentKeyError, match="no agent key at"):
        load_key(path)
    key = load_key(path, create=True)
    assert len(key) == 64 and stat.S_IMODE(path.stat().st_mode) == 0o600
    assert load_key(path) == key
    path.chmod(0o644)
    with pytest.raises(AgentKeyError, match="readable by others"):
        load_key(path)


def test_an_agent_runs_the_request_with_its_own_host_s_settings(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ON_AGENT", "kept")
    monkeypatch.setenv("DROPPED", "by the launch")
    monkeypatch.setenv(SUPERVISOR_SOCKET, "/launcher/socket")
    params = "/tmp/launchkit-x/params_abc.yaml"
    spec = ProcessSpec(
        "rsp",
        [sys.executable, "-m", "node", "--params-file", params],
        env={"ROS_DOMAIN_ID": "7"},
        env_changes={"ADDED": "1", "DROPPED": None},
        files={params: "rsp:\n  ros__parameters: {}\n"},
    )
    fields = encode_spec(spec)
    fields["python"] = "/other/host/python"  # as if the launcher ran another interpreter
    fields["cmd"][0] = "/other/host/python"
    built = build_spec("rsp-2", fields, tmp_path, "tcp/127.0.0.1:9999")
    assert built.cmd[0] == sys.executable
    local = tmp_path / "rsp-2-params_abc.yaml"
    assert built.cmd[-1] == str(local) and local.read_text().startswith("rsp:")
    env = built.env
    assert env["ON_AGENT"] == "kept" and env["ADDED"] == "1" and "DROPPED" not in env
    assert env["ROS_DOMAIN_ID"] == "7" and env[ROUTER] == "tcp/127.0.0.1:9999"
    assert SUPERVISOR_SOCKET not in env and env["LAUNCHKIT_ROUTER_AUTOSTART"] == "0"
    with pytest.raises(FileNotFoundError, match="no folder /nowhere on this host"):
        build_spec("x-1", {**fields, "cwd": "/nowhere"}, tmp_path, "tcp/127.0.0.1:9999")


def test_groups_mark_their_processes_for_a_machine(evaluate_xml: Any) -> None:
    result = evaluate_xml(
        """<launch>
  <arg name="laptop" default="laptop-1"/>
  <executable cmd="true" name="here"/>
  <group machine="$(var laptop)">
    <executable cmd="true" name="there"/>
    <group><executable cmd="true" name="nested"/></group>
    <group machine=""><executable cmd="true" name="back_home"/></group>
    <group forwarding="false"><executable cmd="true" name="reset"/></group>
  </group>
  <executable cmd="true" name="after"/>
</launch>"""
    )
    machines = {p.name: p.machine for p in result.processes}
    assert machines == {
        "here": "",
        "there": "laptop-1",
        "nested": "laptop-1",
        "back_home": "",
        "reset": "laptop-1",
        "after": "",
    }
    with pytest.raises(LaunchkitError, match=r"machine 'a b' is not a valid agent name") as error:
        evaluate_xml('<launch><group machine="a b"><executable cmd="true"/></group></launch>')
    assert error.value.location is not None and error.value.location.line == 1


class FakeAgents:
    """An agent stand-in: a started process says hello, then runs until signalled (it exits
    with the signal) or, if ``quits``, exits 3 by itself."""

    def __init__(self, quits: bool = False, ignore_kill: bool = False) -> None:
        self.quits = quits
        self.ignore_kill = ignore_kill
        self.signals: list[int] = []
        self.starts = 0
        self.may_quit = threading.Event()  # a quitting process waits for it (a test clears it)
        self.may_quit.set()

    def start(self, process: RemoteProcess) -> int:
        self.starts += 1
        incarnation = process.incarnation

        process.instance = "run-1"

        def run() -> None:
            say(process, incarnation, {"kind": "line", "stream": "stdout", "text": "hello"})
            say(process, incarnation, {"kind": "line", "stream": "stderr", "text": "warn"})
            if self.quits and self.may_quit.wait(10):
                say(process, incarnation, {"kind": "exit", "code": 3})

        threading.Thread(target=run).start()
        return 4000 + self.starts

    def signal(self, process: RemoteProcess, signum: int) -> None:
        self.signals.append(signum)
        if signum == signal.SIGKILL and self.ignore_kill:
            return
        say(process, process.incarnation, {"kind": "exit", "code": -signum})


_SEQ = iter(range(1, 1_000_000))


def say(process: RemoteProcess, incarnation: int, event: dict[str, Any]) -> None:
    """Deliver ``event`` as the agent's run ``run-1`` would, numbered."""
    process.deliver("run-1", incarnation, {**event, "seq": next(_SEQ)})


def _drain(process: RemoteProcess, deadline: float = 10.0) -> list[str]:
    lines: list[str] = []
    end = time.monotonic() + deadline
    while process.streams and time.monotonic() < end:
        for fd in list(process.streams):
            got, eof = process.read(fd)
            lines.extend(got)
            if eof:
                process.close_stream(fd)
        time.sleep(0.01)
    return lines


def test_a_remote_process_turns_events_into_lines_and_an_exit() -> None:
    agents = FakeAgents(quits=True)
    process = RemoteProcess(agents, ProcessSpec("w", ["w"], {}, machine="h"), "w-1", 1)
    process.spawn()
    assert process.pid == 4001 and process.pidfd is not None
    assert sorted(_drain(process)) == ["hello", "warn"]
    assert process.poll() == 3 and os.read(process.pidfd, 1) == b"x"
    say(process, 1, {"kind": "line", "stream": "stdout", "text": "late"})  # ignored
    process.close_pidfd()
    agents.may_quit.clear()  # the new incarnation runs until the test lets it quit
    process.spawn()  # a respawn: a new incarnation, new pipes
    assert process.incarnation == 2 and process.poll() is None
    agents.may_quit.set()
    _drain(process)
    assert process.poll() == 3


def test_a_remote_process_takes_only_its_agent_run_s_next_events() -> None:
    class SilentAgents(FakeAgents):
        def start(self, process: RemoteProcess) -> int:
            process.instance = "run-1"
            return 4000

    process = RemoteProcess(SilentAgents(), ProcessSpec("w", ["w"], {}, machine="h"), "w-1", 1)
    process.spawn()
    exit_event = {"kind": "exit", "code": 3, "seq": 10_000_000}
    process.deliver("another-run", 1, exit_event)  # sealed by an earlier run of the agent
    process.deliver("run-1", 2, exit_event)  # for another incarnation
    assert process.poll() is None
    process.deliver("run-1", 1, {"kind": "line", "stream": "stdout", "text": "x", "seq": 1})
    process.deliver("run-1", 1, {**exit_event, "seq": 1})  # a copy of an old number
    assert process.poll() is None
    process.deliver("run-1", 1, {**exit_event, "seq": 2})
    assert process.poll() == 3
    process.close_pidfd()
    _drain(process)


def test_an_unconfirmed_kill_gives_the_process_up(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(remote_process, "KILL_WAIT", 0.2)
    process = RemoteProcess(
        FakeAgents(ignore_kill=True), ProcessSpec("w", ["w"], {}, machine="h"), "w-1", 1
    )
    process.spawn()
    process.kill_leftovers()
    process.reap()
    assert process.poll() == LOST
    assert "[launchkit] agent h did not confirm SIGKILL" in "\n".join(_drain(process))
    process.close_pidfd()


def test_the_supervisor_runs_remote_processes_like_its_own(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    agents = FakeAgents(quits=True)
    monkeypatch.setattr(
        RemoteLaunch,
        "factory",
        lambda self, spec, label, index: RemoteProcess(agents, spec, label, index),
    )
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "log"))
    launch = tmp_path / "remote.launch.xml"
    launch.write_text(
        '<launch><group machine="h"><executable cmd="/nonexistent/on/this/host" name="w" '
        'output="screen" respawn="true" respawn_max_retries="1"/></group></launch>'
    )
    out = io.StringIO()
    assert api.run(launch, stream=out) == 0
    text = out.getvalue()
    assert text.count("[w-1] hello") == 2, text  # the first run and one respawn
    assert "[INFO] [w-1]: process started with pid [4001]" in text
    assert "[ERROR] [w-1]: process has died [pid 4002, exit code 3" in text
    assert "[WARNING] [w-1]: not respawning: 1 retries used" in text
