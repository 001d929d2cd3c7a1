"""Services and clients, the parameter services, the graph and sim time, across sessions."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest
from launchkit.ros.msgs.rcl_interfaces.srv import GetParameters, ListParameters, SetParameters
from launchkit.ros.msgs.rosgraph_msgs.msg import Clock
from launchkit.ros.msgs.std_srvs.srv import SetBool
from ros_helpers import spin_until

from launchkit.ros import Node, Parameter, spin_until_future_complete
from launchkit.ros.context import Context
from launchkit.ros.msgs import get_message
from launchkit.ros.services import ServiceCallError


def _serve_in_thread(node: Node) -> Callable[[], None]:
    import threading

    stop = threading.Event()

    def run() -> None:
        from launchkit.ros import spin_once

        while not stop.is_set():
            spin_once(node, timeout_sec=0.05)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()

    def halt() -> None:
        stop.set()
        thread.join(timeout=5)

    return halt


def test_call_and_call_async(contexts: Callable[[], Context]) -> None:
    server = Node("server", context=contexts())

    def toggle(request: Any, response: Any) -> Any:
        response.success = request.data
        response.message = f"set to {request.data}"
        return response

    server.create_service(SetBool, "toggle", toggle)
    client_node = Node("client", context=contexts())
    client = client_node.create_client(SetBool, "/toggle")
    assert client.wait_for_service(timeout_sec=10)
    halt = _serve_in_thread(server)
    try:
        assert client.call(SetBool.Request(data=True), timeout_sec=10).message == "set to True"
        future = client.call_async(SetBool.Request(data=False))
        spin_until_future_complete(client_node, future, timeout_sec=10)
        assert future.done() and future.result().success is False
    finally:
        halt()


def test_failing_service_reports_an_error(contexts: Callable[[], Context]) -> None:
    server = Node("bad_server", context=contexts())

    def broken(request: Any, response: Any) -> Any:
        return None

    server.create_service(SetBool, "broken", broken)
    client = Node("c", context=contexts()).create_client(SetBool, "broken")
    assert client.wait_for_service(timeout_sec=10)
    future = client.call_async(SetBool.Request())
    with pytest.raises(TypeError):
        spin_until(server, future.done, 10, "the request to reach the server")
    assert future.wait(10)
    with pytest.raises(ServiceCallError, match="expected std_srvs/srv/SetBool_Response"):
        future.result()


def test_missing_service_times_out(contexts: Callable[[], Context]) -> None:
    client = Node("lonely", context=contexts()).create_client(SetBool, "nobody")
    assert client.wait_for_service(timeout_sec=0.2) is False


def test_parameter_services(contexts: Callable[[], Context]) -> None:
    node = Node("driver", context=contexts(), parameter_overrides=[Parameter("rate", value=20)])
    node.declare_parameter("rate", 10)
    node.declare_parameter("wheel.radius", 0.1)
    other = Node("tool", context=contexts())
    halt = _serve_in_thread(node)
    try:
        lister = other.create_client(ListParameters, "/driver/list_parameters")
        assert lister.wait_for_service(timeout_sec=10)
        names = lister.call(ListParameters.Request(), timeout_sec=10).result.names
        # in declaration order, as rclpy lists them (use_sim_time when the node is made)
        assert names == ["use_sim_time", "rate", "wheel.radius"]
        setter = other.create_client(SetParameters, "/driver/set_parameters")
        assert setter.wait_for_service(timeout_sec=10)
        value = Parameter("rate", value=30).to_msg_value()
        param_cls = get_message("rcl_interfaces/msg/Parameter")
        good, bad = setter.call(
            SetParameters.Request(
                parameters=[
                    param_cls(name="rate", value=value),
                    param_cls(
                        name="wheel.radius", value=Parameter("x", value="big").to_msg_value()
                    ),
                ]
            ),
            timeout_sec=10,
        ).results
        assert good.successful and not bad.successful
        getter = other.create_client(GetParameters, "/driver/get_parameters")
        assert getter.wait_for_service(timeout_sec=10)
        values = getter.call(GetParameters.Request(names=["rate", "wheel.radius"]), timeout_sec=10)
        assert values.values[0].integer_value == 30
        assert values.values[1].double_value == 0.1
    finally:
        halt()


def test_graph_sees_nodes_come_and_go(contexts: Callable[[], Context]) -> None:
    watcher = Node("watcher", context=contexts())
    other = Node("visitor", namespace="/robot", context=contexts())
    graph = watcher.context.graph
    assert graph.wait_for(
        lambda: ("visitor", "/robot") in watcher.get_node_names_and_namespaces(), 10
    )
    other.destroy_node()
    assert graph.wait_for(lambda: "visitor" not in watcher.get_node_names(), 10)


def test_sim_time_follows_clock(contexts: Callable[[], Context]) -> None:
    sim = Node("sim", context=contexts())
    clock_pub = sim.create_publisher(Clock, "/clock", 10)
    node = Node(
        "timed", context=contexts(), parameter_overrides=[Parameter("use_sim_time", value=True)]
    )
    assert node.get_clock().now().nanoseconds == 0
    ticks: list[int] = []
    node.create_timer(1.0, lambda: ticks.append(node.get_clock().now().nanoseconds))
    assert clock_pub.wait_for_subscriptions(1, timeout_sec=10)
    stamp = get_message("builtin_interfaces/msg/Time")
    seconds = [0]

    def advance() -> bool:
        seconds[0] += 1
        clock_pub.publish(Clock(clock=stamp(sec=seconds[0], nanosec=0)))
        return len(ticks) >= 2

    spin_until(node, advance, 10, "two sim-time timer ticks")
    assert ticks[0] >= 1_000_000_000 and ticks[1] - ticks[0] >= 1_000_000_000


def test_raw_service_and_client_pass_bytes_and_may_answer_later(
    contexts: Callable[[], Context],
) -> None:
    from launchkit.ros.msgs import deserialize, serialize
    from launchkit.ros.task import Future

    server = Node("raw_server", context=contexts())
    later: list[tuple[bytes, Future]] = []

    def answer_later(request: bytes) -> Future:
        future = Future()
        later.append((request, future))
        return future

    server.create_service(SetBool, "/deferred", answer_later, raw=True)
    halt = _serve_in_thread(server)
    try:
        client = Node("raw_client", context=contexts()).create_client(
            SetBool, "/deferred", raw=True
        )
        assert client.wait_for_service(timeout_sec=10)
        request = serialize(SetBool.Request(data=True), "std_srvs/srv/SetBool_Request")
        pending = client.call_async(request)
        spin_until(client.node, lambda: bool(later), 10, "the raw request at the server")
        assert later[0][0] == request and not pending.done()
        response = SetBool.Response(success=True, message="answered later")
        later[0][1].set_result(serialize(response, "std_srvs/srv/SetBool_Response"))
        assert pending.wait(10), "the deferred answer never reached the client"
        decoded = deserialize(pending.result(), "std_srvs/srv/SetBool_Response")
        assert (decoded.success, decoded.message) == (True, "answered later")
    finally:
        halt()


def test_keep_last_requests_beyond_the_depth_discard_the_oldest_as_rmw_zenoh(
    contexts: Callable[[], Context], capsys: pytest.CaptureFixture[str]
) -> None:
    from launchkit.ros import QoSProfile

    server = Node("slow_server", context=contexts())
    server.create_service(
        SetBool,
        "/busy",
        lambda q, r: SetBool.Response(success=q.data),
        qos_profile=QoSProfile(depth=1),
    )
    client = Node("eager_client", context=contexts()).create_client(SetBool, "/busy")
    assert client.wait_for_service(timeout_sec=10)
    # the server does not spin yet: the second request discards the first
    first = client.call_async(SetBool.Request(data=False), timeout_sec=30)
    second = client.call_async(SetBool.Request(data=True), timeout_sec=30)
    assert first.wait(10), "the first request was never discarded"
    assert isinstance(first.exception(), ServiceCallError)
    spin_until(server, second.done, 10, "the second request to be answered")
    assert second.result().success is True
    assert "Query queue depth of 1 reached" in capsys.readouterr().err


def test_a_server_answers_as_soon_as_its_token_is_seen(
    contexts: Callable[[], Context], router: str
) -> None:
    # a client reacting to the SS token at once must find the queryable behind it (the token
    # is declared after the queryable, on the same link to the router)
    import queue

    import zenoh

    from launchkit.ros.keyexpr import LIVELINESS_PREFIX, parse_token
    from launchkit.ros.session import close_session, open_session, peer_config

    watcher = open_session(peer_config(router))
    answered: queue.Queue[tuple[str, int]] = queue.Queue()
    request = SetBool.Request(data=True)
    from launchkit.ros.msgs import serialize

    payload = serialize(request, "std_srvs/srv/SetBool_Request")

    def on_token(sample: zenoh.Sample) -> None:
        token = parse_token(str(sample.key_expr))
        if token is None or token.kind != "SS" or sample.kind != zenoh.SampleKind.PUT:
            return
        from launchkit.ros.keyexpr import topic_key

        key = topic_key(token.domain, token.topic, token.type_name, token.type_hash)
        replies = list(watcher.get(key, payload=payload, timeout=10.0))
        answered.put((token.topic, len(replies)))

    subscriber = watcher.liveliness().declare_subscriber(f"{LIVELINESS_PREFIX}/**", on_token)
    try:
        server = Node("eager_server", context=contexts(), start_parameter_services=False)
        halt = _serve_in_thread(server)
        try:
            for i in range(10):
                server.create_service(SetBool, f"/eager_{i}", lambda q, r: r)
            results = dict(answered.get(timeout=30) for _ in range(10))
        finally:
            halt()
        assert results == {f"/eager_{i}": 1 for i in range(10)}
    finally:
        subscriber.undeclare()
        close_session(watcher)
