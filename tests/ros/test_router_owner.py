"""A router port held by another local user is refused, not silently joined (issue #17).

The other user is ``nobody``: a child process drops to its uid before it listens (the tests
run as root; elsewhere they are skipped, saying why).
"""

from __future__ import annotations

import ipaddress
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_helpers import NODES_DIR, Child, demo_package, stderr_line

from launchkit.ros.context import Context
from launchkit.ros.port_owner import _decode_address, find_listener
from launchkit.ros.router import start_router
from launchkit.ros.router_access import ForeignRouterError
from launchkit.testing._isolation import free_loopback_port

NOBODY = 65534

_LISTEN_AS_NOBODY = """
import os, socket, sys, time
os.setgroups([]); os.setgid({uid}); os.setuid({uid})
s = socket.socket(); s.bind(("127.0.0.1", {port})); s.listen()
print("listening", flush=True)
sys.stdin.read()
"""


_ROUTER_AS_NOBODY = """
import json, os, sys, threading, time, encodings.idna
import zenoh
os.setgroups([]); os.setgid({uid}); os.setuid({uid})
config = zenoh.Config()
config.insert_json5("mode", '"router"')
config.insert_json5("listen/endpoints", json.dumps(["tcp/127.0.0.1:{port}"]))
config.insert_json5("scouting/multicast/enabled", "false")
session = zenoh.open(config)
heard = session.declare_subscriber("**", lambda sample: print("heard", sample.key_expr, flush=True))
print("listening", flush=True)
sys.stdin.read()
"""


@pytest.fixture
def foreign_endpoint() -> Iterator[str]:
    """An endpoint on loopback where a process of user ``nobody`` listens."""
    if os.geteuid() != 0:
        pytest.skip("needs root, to start a listener as another user")
    port = free_loopback_port()
    owner = subprocess.Popen(
        [sys.executable, "-c", _LISTEN_AS_NOBODY.format(uid=NOBODY, port=port)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert owner.stdout is not None and owner.stdout.readline() == "listening\n"
        yield f"tcp/127.0.0.1:{port}"
    finally:
        owner.kill()
        owner.communicate()  # reaps it and closes its pipes


def test_the_owner_of_a_listening_port_is_found(foreign_endpoint: str) -> None:
    port = int(foreign_endpoint.rpartition(":")[2])
    listener = find_listener("127.0.0.1", port)
    assert listener is not None and listener.uid == NOBODY and listener.user == "nobody"
    assert find_listener("localhost", port) == listener
    assert find_listener("127.0.0.1", free_loopback_port()) is None


def test_kernel_addresses_are_decoded() -> None:
    assert _decode_address("0100007F:1D17") == (ipaddress.ip_address("127.0.0.1"), 7447)
    v6_loopback = "00000000000000000000000001000000:0050"
    assert _decode_address(v6_loopback) == (ipaddress.ip_address("::1"), 80)
    mapped = "0000000000000000FFFF00000100007F:1D17"
    assert _decode_address(mapped)[0] == ipaddress.ip_address("::ffff:127.0.0.1")


def test_a_launch_refuses_another_users_router(foreign_endpoint: str, tmp_path: Path) -> None:
    demo_package(tmp_path / "prefix")
    launch = tmp_path / "talk.launch.xml"
    launch.write_text('<launch><node pkg="demo" exec="talker"/></launch>\n')
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "run", str(launch), "--router", foreign_endpoint],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "AMENT_PREFIX_PATH": str(tmp_path / "prefix")},
    )
    output = result.stdout + result.stderr
    assert result.returncode == 1, output
    assert (
        f"error: the ROS router port {foreign_endpoint} is held by another user "
        f"(nobody, uid {NOBODY}): refusing to join it" in output
    )
    assert "LAUNCHKIT_ROUTER_TRUSTED_USERS=nobody" in output
    assert "talker-1" not in output  # nothing was started


def test_a_command_refuses_another_users_router(foreign_endpoint: str) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "launchkit", "topic", "list", "--router", foreign_endpoint],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 1
    assert result.stderr.startswith(f"error: the ROS router port {foreign_endpoint} is held by")
    assert "Traceback" not in result.stderr


def test_a_node_refuses_another_users_router(foreign_endpoint: str) -> None:
    context = Context(router=foreign_endpoint)
    context.init([])
    try:
        with pytest.raises(ForeignRouterError, match="held by another user"):
            _ = context.session
    finally:
        context.shutdown()


def test_a_trusted_users_router_is_joined(
    foreign_endpoint: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    with pytest.raises(ForeignRouterError):
        start_router(foreign_endpoint)
    monkeypatch.setenv("LAUNCHKIT_ROUTER_TRUSTED_USERS", "someone-unknown, nobody")
    handle = start_router(foreign_endpoint)
    assert not handle.hosted


def test_nodes_and_commands_refuse_another_users_router_after_losing_theirs() -> None:
    if os.geteuid() != 0:
        pytest.skip("needs root, to start a router as another user")
    port = free_loopback_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    ours = start_router(endpoint)
    env = {"LAUNCHKIT_ROUTER": endpoint, "LAUNCHKIT_ROUTER_AUTOSTART": "0"}
    talker = Child([str(NODES_DIR / "talker.py")], env)
    command = [
        "-m", "launchkit", "topic", "pub", "/chatter", "std_msgs/msg/String", "{data: pub}",
        "-r", "50", "--router", endpoint,
    ]  # fmt: skip
    publisher = Child(command, env)
    foreign: subprocess.Popen[str] | None = None
    try:
        talker.expect("talker ready")
        publisher.expect("publishing")
        ours.close()  # the owner's router dies; another user's takes the port
        foreign = subprocess.Popen(
            [sys.executable, "-c", _ROUTER_AS_NOBODY.format(uid=NOBODY, port=port)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        assert foreign.stdout is not None and foreign.stdout.readline() == "listening\n"
        for child in (talker, publisher):
            assert child.proc.wait(timeout=30) == 1, "it kept talking through the other router"
            line = stderr_line(child, "after losing its router", timeout=5)
            assert f"the ROS router port {endpoint} is held by another user (nobody" in line
        foreign.kill()
        heard = foreign.communicate()[0]
        assert "heard" not in heard, f"the other user's router heard: {heard[:300]}"
    finally:
        for child in (talker, publisher):
            child.stop()
        if foreign is not None:
            foreign.kill()
            foreign.communicate()
        ours.close()
