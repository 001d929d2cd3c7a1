"""Launching on another host: a launch file's ``<group machine="hostb">`` runs on host B's
agent, supervised from host A's launcher; Ctrl-C, a killed launcher and a killed agent leave
nothing running on B."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from certs import Authority
from netns import Host, Hosts, Proc

from launchkit.remote.keys import load_key

ROS_NODES = Path(__file__).resolve().parent.parent / "ros"
sys.path.insert(0, str(ROS_NODES))
from ros_helpers import demo_package  # noqa: E402

LAUNCH = """<launch>
  <arg name="where" default="hostb"/>
  <node pkg="demo" exec="talker"/>
  <group machine="$(var where)">
    <executable cmd="sh -c 'echo remote-hello from $HOSTMARK; exec sleep 1000'"
                name="sleeper" output="screen"/>
    <node pkg="demo" exec="listener" output="screen"/>
  </group>
</launch>
"""


@pytest.fixture
def setup(tmp_path: Path) -> dict[str, str]:
    """A launch file, the demo package and the agent key's path, as environment."""
    demo_package(tmp_path / "prefix")
    (tmp_path / "remote.launch.xml").write_text(LAUNCH)
    return {
        "AMENT_PREFIX_PATH": str(tmp_path / "prefix"),
        "LAUNCHKIT_AGENT_KEY": str(tmp_path / "agent.key"),
        "LAUNCH": str(tmp_path / "remote.launch.xml"),
    }


def agent(host: Host, env: dict[str, str]) -> Proc:
    """``launchkit agent --name hostb`` on ``host``, its router listening on the link."""
    proc = host.launchkit(
        "agent", "--name", "hostb", "--listen", f"tcp/{host.address}:7448",
        env={**env, "HOSTMARK": "host-b"},
    )  # fmt: skip
    proc.expect("agent hostb ready")
    return proc


def launcher(hosts: Hosts, env: dict[str, str], *args: str) -> Proc:
    """``launchkit run`` on host A, its router connected to host B's."""
    return hosts.a.launchkit(
        "run", env["LAUNCH"], "--connect", f"tcp/{hosts.b.address}:7448", *args,
        env={**env, "HOSTMARK": "host-a"},
    )  # fmt: skip


def heard_across(hosts: Hosts, env: dict[str, str]) -> tuple[Proc, Proc]:
    """Host B's agent and host A's launch using it (a 2 s remote grace), once B's listener
    hears A's talker."""
    host_agent = agent(hosts.b, env)
    run = launcher(hosts, env, "--remote-grace", "2")
    run.expect("[listener-3] heard: hello")
    return host_agent, run


def remote_leftovers(host: Host) -> list[str]:
    """Command lines of the launch's processes still running on ``host``."""
    found = []
    for pid in host.pids():
        try:
            command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
        except OSError:
            continue
        if "sleep 1000" in command or "remote-hello" in command or "demo/listener" in command:
            found.append(command)
    return found


def wait_until_gone(host: Host, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while left := remote_leftovers(host):
        assert time.monotonic() < deadline, f"still running on {host.name}: {left}"
        time.sleep(0.1)


def test_a_remote_launch_runs_streams_and_stops_everywhere(
    hosts: Hosts, setup: dict[str, str]
) -> None:
    agent(hosts.b, setup)
    run = launcher(hosts, setup)
    run.expect("[sleeper-2] remote-hello from host-b")  # ran on B, output back with its prefix
    run.expect("[listener-3] heard: hello")  # B's listener hears A's talker
    nodes = hosts.b.run("node", "list")
    assert "/talker\n" in nodes and "/listener\n" in nodes and "/launchkit/agents/hostb\n" in nodes
    assert remote_leftovers(hosts.b) and not remote_leftovers(hosts.a)
    assert run.stop() == 0  # Ctrl-C
    run.rest()
    finished = [line for line in run.seen if "process has finished" in line]
    assert any("[sleeper-2]" in line for line in finished), run.seen[-20:]
    assert any("[listener-3]" in line for line in finished), run.seen[-20:]
    assert remote_leftovers(hosts.b) == []


def test_a_killed_launcher_s_remote_processes_stop_after_the_grace_period(
    hosts: Hosts, setup: dict[str, str]
) -> None:
    host_agent, run = heard_across(hosts, setup)
    run.signal(signal.SIGKILL)
    host_agent.expect("lost the launcher of launch")
    host_agent.expect("gone: stopping its processes")
    wait_until_gone(hosts.b, timeout=30)
    assert host_agent.proc.poll() is None  # the agent itself goes on


def test_an_agent_killed_leaves_no_orphans_and_the_launch_hears_of_it(
    hosts: Hosts, setup: dict[str, str]
) -> None:
    host_agent, run = heard_across(hosts, setup)
    host_agent.signal(signal.SIGKILL)
    wait_until_gone(hosts.b, timeout=30)  # its orphan guard killed every group
    agent(hosts.b, setup)  # a new run of the agent
    run.expect("[sleeper-2]: process has died")
    assert any("agent hostb" in line for line in run.seen[-10:]), run.seen[-10:]
    assert run.stop() == 0


def test_a_missing_key_or_agent_fails_the_launch_in_one_line(
    hosts: Hosts, setup: dict[str, str]
) -> None:
    run = launcher(hosts, setup)
    line = run.expect("could not start process")
    assert f"no agent key at {setup['LAUNCHKIT_AGENT_KEY']}" in line
    assert run.proc.wait(timeout=30) == 1
    load_key(Path(setup["LAUNCHKIT_AGENT_KEY"]), create=True)
    run = launcher(hosts, {**setup, "LAUNCHKIT_AGENT_TIMEOUT": "2"})
    run.expect("waiting for agent hostb")
    line = run.expect("could not start process")
    assert "no agent hostb on the graph after 2 s" in line
    assert run.proc.wait(timeout=30) == 1


def test_print_shows_which_host_runs_what(setup: dict[str, str]) -> None:
    printed = subprocess.run(
        [sys.executable, "-m", "launchkit", "run", setup["LAUNCH"], "where:=laptop", "--print"],
        capture_output=True,
        text=True,
        env={**os.environ, **setup},
        timeout=60,
    )
    assert printed.returncode == 0, printed.stderr
    blocks = printed.stdout.split("\n\n") if "\n\n" in printed.stdout else [printed.stdout]
    text = "\n".join(blocks)
    talker, sleeper = text.index("node talker"), text.index("process sleeper")
    assert "machine:" not in text[talker:sleeper]
    assert "machine: laptop (run by its launchkit agent)" in text[sleeper:]


def test_a_cut_link_stops_the_remote_processes_after_the_grace_period(
    hosts: Hosts, setup: dict[str, str]
) -> None:
    fast = {**setup, "ZENOH_CONFIG_OVERRIDE": "transport/link/tx/lease=2000"}
    host_agent, run = heard_across(hosts, fast)
    hosts.a.set_link(False)
    host_agent.expect("lost the launcher of launch")
    host_agent.expect("gone: stopping its processes")
    wait_until_gone(hosts.b, timeout=30)
    # the launcher, cut off too, gives them up after the same grace period
    line = run.expect("[sleeper-2]: process has died")
    assert "exit code 255" in line
    assert any("lost agent hostb for 2 s" in seen for seen in run.seen[-15:]), run.seen[-15:]
    hosts.a.set_link(True)
    assert run.stop() == 0


def test_only_the_launchers_an_agent_names_reach_it(
    hosts: Hosts, setup: dict[str, str], tmp_path: Path
) -> None:
    ca = Authority("robot-ca")
    a_certs = ca.host_folder(tmp_path / "a", "host-a", hosts.a.address)
    b_certs = ca.host_folder(tmp_path / "b", "host-b", hosts.b.address)
    link = f"tls/{hosts.b.address}:7448"

    def agent_admitting(names: str) -> Proc:
        proc = hosts.b.launchkit(
            "agent", "--name", "hostb", "--listen", link, "--mtls", str(b_certs),
            "--launchers", names, env={**setup, "HOSTMARK": "host-b"},
        )  # fmt: skip
        admitted = names.replace(",", ", ")
        proc.expect(f"access control: only this host and {admitted} may use this router")
        proc.expect("agent hostb ready")
        return proc

    def launch(*env: tuple[str, str]) -> Proc:
        return hosts.a.launchkit(
            "run", setup["LAUNCH"], "--connect", link, "--mtls", str(a_certs),
            env={**setup, "HOSTMARK": "host-a", **dict(env)},
        )  # fmt: skip

    shut_out = agent_admitting("host-c")  # host A has the key and a certificate of the CA
    run = launch(("LAUNCHKIT_AGENT_TIMEOUT", "3"))
    assert "no agent hostb on the graph after 3 s" in run.expect("could not start process")
    assert run.proc.wait(timeout=30) == 1
    assert shut_out.stop() == 0
    agent_admitting("host-a,host-c")
    run = launch()
    run.expect("[sleeper-2] remote-hello from host-b")
    assert run.stop() == 0
    assert remote_leftovers(hosts.b) == []
