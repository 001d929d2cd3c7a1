"""Faults: router restarts, dying peers, prompt exit with advanced subscribers, loopback only."""

from __future__ import annotations

import os
from pathlib import Path

from ros_helpers import NODES_DIR, Child

from launchkit.ros.router import start_router
from launchkit.ros.session import close_session, open_session, peer_config
from launchkit.testing._isolation import free_loopback_port, router_endpoint


def test_nodes_reconnect_after_the_router_restarts(children: list[Child], monkeypatch) -> None:
    endpoint = router_endpoint(free_loopback_port())
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    router = start_router(endpoint)
    try:
        talker = Child([str(NODES_DIR / "talker.py")])
        children.append(talker)
        first = Child([str(NODES_DIR / "listener.py")])
        children.append(first)
        first.expect("heard: hello", timeout=15)

        router.close()
        router = start_router(endpoint)
        assert router.hosted

        # the old listener keeps hearing (peers talk directly) ...
        first.expect("heard: hello", timeout=15)
        # ... and a node started after the restart finds the talker through the new router
        second = Child([str(NODES_DIR / "listener.py"), "--ros-args", "-r", "__node:=second"])
        children.append(second)
        second.expect("heard: hello", timeout=15)
    finally:
        router.close()


def test_listener_survives_its_talker_dying(router: str, children: list[Child]) -> None:
    listener = Child([str(NODES_DIR / "listener.py")])
    children.append(listener)
    talker = Child([str(NODES_DIR / "talker.py")])
    children.append(talker)
    listener.expect("heard: hello", timeout=15)
    talker.proc.kill()
    talker.proc.wait()
    replacement = Child([str(NODES_DIR / "talker.py")])
    children.append(replacement)
    replacement.expect("talker ready", timeout=15)
    listener.expect("heard: hello 1", timeout=15)  # the new talker's count starts again
    assert listener.proc.poll() is None


def test_node_with_advanced_subscriber_exits_on_sigint(router: str, children: list[Child]) -> None:
    node = Child([str(NODES_DIR / "latched_listener.py")])
    children.append(node)
    node.expect("latched_listener ready", timeout=15)
    assert node.stop(timeout=5) == 0, "the node did not exit by itself after SIGINT"
    assert any("latched_listener done" in line for line in node.out.drain())


def _listening_addresses(pid: int) -> list[tuple[str, str]]:
    """(protocol, local address) of every listening TCP socket and bound UDP socket of ``pid``."""
    inodes = set()
    for fd in Path(f"/proc/{pid}/fd").iterdir():
        target = os.readlink(fd) if fd.is_symlink() else ""
        if target.startswith("socket:["):
            inodes.add(target[8:-1])
    found = []
    for proto in ("tcp", "tcp6", "udp", "udp6"):
        lines = Path(f"/proc/{pid}/net/{proto}").read_text().splitlines()[1:]
        for line in lines:
            fields = line.split()
            local, state, inode = fields[1], fields[3], fields[9]
            if inode in inodes and (proto.startswith("udp") or state == "0A"):  # 0A: LISTEN
                found.append((proto, local))
    return found


def test_sessions_listen_on_loopback_only(router: str) -> None:
    config = peer_config()
    assert config.get_json("scouting/multicast/enabled") == "false"
    session = open_session(config)
    try:
        found = _listening_addresses(os.getpid())
        # the router (this process hosts it) and the peer session: TCP listeners, no UDP
        assert [p for p, _ in found if p.startswith("udp")] == []
        tcp = [address for p, address in found if p.startswith("tcp")]
        assert len(tcp) >= 2
        loopback_v4 = "0100007F:"  # 127.0.0.1 as /proc/net/tcp writes it
        assert all(address.startswith(loopback_v4) for address in tcp), tcp
    finally:
        close_session(session)
