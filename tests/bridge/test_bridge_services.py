"""Services through ``launchkit bridge``: an rclpy client calls a launchkit server (and a
launchkit node's parameter services), a launchkit client calls an rclpy server."""

from __future__ import annotations

from typing import Any

import pytest
from bridge_helpers import BridgeProcess, DdsPeer, LaunchkitPeer, wait_until
from launchkit.ros.msgs.std_srvs.srv import SetBool

# rclpy's type support imports lark, which imports the deprecated sre_parse
pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

WAIT = 30.0


def _call(client: Any, request: Any) -> Any:
    """Call from the test thread (the peer's executor spins elsewhere)."""
    assert client.wait_for_service(timeout_sec=WAIT), f"{client.srv_name} never appeared"
    future = client.call_async(request)
    wait_until(future.done, WAIT, f"an answer from {client.srv_name}")
    return future.result()


def test_an_rclpy_client_calls_a_launchkit_server(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from std_srvs.srv import SetBool as RclpySetBool

    calls: list[bool] = []

    def serve(request: Any, response: Any) -> Any:
        calls.append(request.data)
        return SetBool.Response(success=request.data, message="answered by launchkit")

    lk.node.create_service(SetBool, "/lk_flag", serve)
    client = dds.node.create_client(RclpySetBool, "/lk_flag")
    response = _call(client, RclpySetBool.Request(data=True))
    assert (response.success, response.message) == (True, "answered by launchkit")
    assert calls == [True]


def test_an_rclpy_client_reads_a_launchkit_nodes_parameters(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rcl_interfaces.srv import GetParameters

    lk.node.declare_parameter("wheel_radius", 0.033)
    client = dds.node.create_client(GetParameters, "/lk_peer/get_parameters")
    response = _call(client, GetParameters.Request(names=["wheel_radius"]))
    assert [v.double_value for v in response.values] == [0.033]


def test_a_launchkit_client_calls_an_rclpy_server(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from std_srvs.srv import SetBool as RclpySetBool

    def serve(request: Any, response: Any) -> Any:
        response.success = not request.data
        response.message = "answered by rclpy"
        return response

    dds.node.create_service(RclpySetBool, "/dds_flag", serve)
    client = lk.node.create_client(SetBool, "/dds_flag")
    assert client.wait_for_service(timeout_sec=WAIT), "/dds_flag never reached launchkit"
    response = client.call(SetBool.Request(data=True), timeout_sec=WAIT)
    assert (response.success, response.message) == (False, "answered by rclpy")
    bridge.wait_line("bridging service /dds_flag (std_srvs/srv/SetBool): launchkit clients")
