"""Routers federate across hosts (network namespaces): topics, services, parameters, the graph,
transient-local latecomers and the CLI work as on one host, and survive router restarts and a
cut link."""

from __future__ import annotations

import time
from pathlib import Path

from netns import Host, Hosts, Proc

NODES = Path(__file__).resolve().parent.parent / "ros" / "nodes"
ROUTER = "tcp/127.0.0.1:7447"
# routers notice a dead link after 3 s instead of Zenoh's 10 (cut-link test)
FAST_LEASE = {"ZENOH_CONFIG_OVERRIDE": "transport/link/tx/lease=3000"}


def router(host: Host, *args: str) -> Proc:
    """``launchkit router`` on ``host``, listening at its loopback for its own nodes."""
    proc = host.launchkit("router", "--router", ROUTER, *args, env=FAST_LEASE)
    proc.expect(f"listening at {ROUTER}")
    return proc


def federate(hosts: Hosts) -> tuple[Proc, Proc]:
    """Router A listens on the link; router B connects to it."""
    a = router(hosts.a, "--listen", f"tcp/{hosts.a.address}:7448")
    b = router(hosts.b, "--connect", f"tcp/{hosts.a.address}:7448")
    b.expect(f"linked to the router at tcp/{hosts.a.address}:7448")
    return a, b


def test_topics_services_graph_and_latecomers_across_hosts(hosts: Hosts) -> None:
    a, _ = federate(hosts)
    a.expect(f"listening on tcp/{hosts.a.address}:7448 without TLS: anyone who can reach")
    # topics, both ways
    hosts.a.start(str(NODES / "talker.py"))
    listener_b = hosts.b.start(str(NODES / "listener.py"))
    listener_b.expect("heard: hello")
    hosts.b.start(
        str(NODES / "talker.py"), "--ros-args", "-r", "__node:=talker_b", "-r", "chatter:=chatter_b"
    )
    listener_a = hosts.a.start(str(NODES / "listener.py"), "--ros-args", "-r", "chatter:=chatter_b")
    listener_a.expect("heard: hello")
    # the graph and parameter services of a node on the other host, from the CLI (a command
    # that has just joined may see part of the graph, as ros2's do: ask again until it all is)
    _until(hosts.b, ["node", "list"], "/talker\n", "/talker_b\n")
    _until(hosts.a, ["topic", "list", "-t"], "/chatter [std_msgs/msg/String]", "/chatter_b")
    _until(hosts.b, ["param", "list", "/talker"], "use_sim_time")
    # a transient-local message published on A before anyone on B listened
    latched = hosts.a.start(str(NODES / "latched_listener.py"))
    latched.expect("latched_listener ready")
    assert hosts.b.run("topic", "echo", "/status", "--once") == "data: up\n---\n"


def test_routers_restart_on_either_side(hosts: Hosts) -> None:
    a, b = federate(hosts)
    hosts.a.start(str(NODES / "talker.py"))
    listener = hosts.b.start(str(NODES / "listener.py"))
    listener.expect("heard: hello")
    assert b.stop() == 0
    b = router(hosts.b, "--connect", f"tcp/{hosts.a.address}:7448")
    b.expect(f"linked to the router at tcp/{hosts.a.address}:7448")
    _hears_again(listener)
    assert a.stop() == 0
    router(hosts.a, "--listen", f"tcp/{hosts.a.address}:7448")
    b.expect(f"linked to the router at tcp/{hosts.a.address}:7448")
    _hears_again(listener)


def test_a_cut_link_mends(hosts: Hosts) -> None:
    _, b = federate(hosts)
    hosts.a.start(str(NODES / "talker.py"))
    listener = hosts.b.start(str(NODES / "listener.py"))
    listener.expect("heard: hello")
    hosts.a.set_link(False)
    b.expect(f"lost the link to the router at tcp/{hosts.a.address}:7448")
    hosts.a.set_link(True)
    b.expect(f"linked to the router at tcp/{hosts.a.address}:7448")
    _hears_again(listener)


def _until(host: Host, command: list[str], *texts: str, timeout: float = 60.0) -> None:
    """Run ``launchkit COMMAND`` on ``host`` until its output holds every text."""
    deadline = time.monotonic() + timeout
    while True:
        out = host.run(*command, check=False)
        if all(text in out for text in texts):
            return
        assert time.monotonic() < deadline, f"`launchkit {' '.join(command)}` said: {out}"


def _hears_again(listener: Proc) -> None:
    """The listener hears a message sent after now (its queue may hold older ones)."""
    listener.rest()
    last = max((int(line.split()[-1]) for line in listener.seen if "heard:" in line), default=0)
    while True:
        line = listener.expect("heard: hello")
        count = int(line.split()[-1])
        if count > last + 1 or count < last:  # a new message (or a restarted talker's)
            return
