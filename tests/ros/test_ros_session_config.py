"""rmw_zenoh's configuration variables: ZENOH_SESSION_CONFIG_URI, ZENOH_ROUTER_CONFIG_URI and
ZENOH_CONFIG_OVERRIDE mean here what they mean to rmw_zenoh 0.2.x (zenoh_config.cpp)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from launchkit.ros.msgs.std_msgs.msg import String
from ros_helpers import spin_until

from launchkit.ros import Node
from launchkit.ros.context import Context
from launchkit.ros.router import start_router
from launchkit.ros.session import (
    ZenohConfigError,
    parse_overrides,
    peer_config,
    router_config,
)
from launchkit.testing._isolation import free_loopback_port, router_endpoint


def test_overrides_split_as_rmw_zenoh_splits_them() -> None:
    text = 'listen/endpoints=["tcp/127.0.0.1:7448"];scouting/multicast/enabled=true;junk;k=;a=b=c'
    assert parse_overrides(text) == [
        ("listen/endpoints", '["tcp/127.0.0.1:7448"]'),
        ("scouting/multicast/enabled", "true"),
        ("a", "b=c"),  # split at the first "=" only; "junk" and "k=" are skipped
    ]
    assert parse_overrides("") == []


def test_override_changes_launchkits_own_session_config(monkeypatch: pytest.MonkeyPatch) -> None:
    override = 'listen/endpoints=["tcp/127.0.0.1:7448"];transport/shared_memory/enabled=false'
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", override)
    config = peer_config("tcp/127.0.0.1:7447")
    assert json.loads(config.get_json("listen/endpoints")) == ["tcp/127.0.0.1:7448"]
    assert json.loads(config.get_json("transport/shared_memory/enabled")) is False
    # what the override leaves alone stays launchkit's
    assert json.loads(config.get_json("connect/endpoints")) == ["tcp/127.0.0.1:7447"]
    assert json.loads(config.get_json("scouting/multicast/enabled")) is False


def test_override_applies_on_top_of_the_config_files(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    session_file = tmp_path / "session.json5"
    session_file.write_text('{ mode: "peer", connect: { endpoints: ["tcp/127.0.0.1:9"] } }')
    router_file = tmp_path / "router.json5"
    router_file.write_text('{ mode: "router", listen: { endpoints: ["tcp/127.0.0.1:10"] } }')
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", str(session_file))
    monkeypatch.setenv("ZENOH_ROUTER_CONFIG_URI", str(router_file))
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", "scouting/gossip/enabled=false")
    session = peer_config("tcp/127.0.0.1:7447")
    assert json.loads(session.get_json("connect/endpoints")) == ["tcp/127.0.0.1:9"]
    assert json.loads(session.get_json("scouting/gossip/enabled")) is False
    router = router_config("tcp/127.0.0.1:7447")
    assert json.loads(router.get_json("listen/endpoints")) == ["tcp/127.0.0.1:10"]
    assert json.loads(router.get_json("scouting/gossip/enabled")) is False


def test_an_invalid_pair_is_ignored_with_a_warning(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", "no/such/key=1;scouting/gossip/enabled=false")
    config = peer_config("tcp/127.0.0.1:7447")
    assert json.loads(config.get_json("scouting/gossip/enabled")) is False
    err = capsys.readouterr().err
    assert "[WARN]" in err and "ZENOH_CONFIG_OVERRIDE" in err and "(no/such/key, 1)" in err


def test_an_unusable_config_file_is_a_user_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    missing = tmp_path / "missing.json5"
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", str(missing))
    with pytest.raises(ZenohConfigError, match=f"ZENOH_SESSION_CONFIG_URI={missing}") as info:
        peer_config()
    assert info.value.exit_status == 2
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", "")  # empty means unset, as in rmw_zenoh
    assert peer_config("tcp/127.0.0.1:7447") is not None


def test_nodes_follow_an_override_to_another_router(monkeypatch: pytest.MonkeyPatch) -> None:
    # LAUNCHKIT_ROUTER names a port where nothing listens; the override sends both nodes to
    # the router that really runs, as ZENOH_CONFIG_OVERRIDE would send rmw_zenoh nodes
    real = router_endpoint(free_loopback_port())
    router = start_router(real)
    assert router.hosted
    monkeypatch.setenv("LAUNCHKIT_ROUTER", router_endpoint(free_loopback_port()))
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["{real}"]')
    contexts = [Context(), Context()]
    try:
        for context in contexts:
            context.init([])
        talker = Node("talker", context=contexts[0])
        listener = Node("listener", context=contexts[1])
        got: list[str] = []
        listener.create_subscription(String, "/chatter", lambda m: got.append(m.data), 10)
        pub = talker.create_publisher(String, "/chatter", 10)

        def publish() -> bool:
            pub.publish(String(data="through the overridden router"))
            return bool(got)

        spin_until(listener, publish, 10, "a message between nodes sent to the real router")
    finally:
        for context in contexts:
            context.shutdown()
        router.close()
