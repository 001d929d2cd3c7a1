"""What the rqt panels get from the viewer's server, without a browser: the node graph from
liveliness tokens (actions grouped), message types' fields for forms, messages as JSON whatever
containers their fields use, and the page protocol's new requests answered (or refused) in one
line."""

from __future__ import annotations

import array
import asyncio
import json
from typing import Any

import numpy as np

from launchkit.ros.keyexpr import Token
from launchkit.ros.message_text import to_data
from launchkit.ros.msgs import get_message
from launchkit.stock.rviz2.graph_view import action_of, describe_graph
from launchkit.stock.rviz2.hub import Hub
from launchkit.stock.rviz2.page_session import PageSession
from launchkit.stock.rviz2.schema import interface_schema


def token(kind: str, node: str, topic: str = "", type_name: str = "") -> Token:
    """A parsed liveliness token of ``node`` (``/ns/name``)."""
    namespace, _, name = node.rpartition("/")
    return Token(
        key=f"{kind}{node}{topic}",
        domain=0,
        zid="z",
        node_id="1",
        entity_id="2",
        kind=kind,
        enclave="/",
        namespace=namespace or "/",
        node_name=name,
        topic=topic,
        type_name=type_name,
    )


FIB = "example_interfaces/action/Fibonacci"


def test_the_graph_lists_nodes_topics_services_and_actions_with_both_sides() -> None:
    tokens = [
        token("NN", "/talker"),
        token("NN", "/robot1/listener"),
        token("NN", "/server"),
        token("NN", "/client"),
        token("MP", "/talker", "/chatter", "std_msgs/msg/String"),
        token("MS", "/robot1/listener", "/chatter", "std_msgs/msg/String"),
        token("SS", "/server", "/add", "std_srvs/srv/Trigger"),
        token("SC", "/client", "/add", "std_srvs/srv/Trigger"),
    ]
    for part in ("send_goal", "cancel_goal", "get_result"):
        suffix = {"send_goal": "_SendGoal", "cancel_goal": "", "get_result": "_GetResult"}[part]
        tokens.append(token("SS", "/server", f"/fib/_action/{part}", FIB + suffix))
        tokens.append(token("SC", "/client", f"/fib/_action/{part}", FIB + suffix))
    for part in ("feedback", "status"):
        tokens.append(token("MP", "/server", f"/fib/_action/{part}", "x/msg/Y"))
        tokens.append(token("MS", "/client", f"/fib/_action/{part}", "x/msg/Y"))
    graph = describe_graph(tokens)
    assert graph["nodes"][1] == {"name": "/robot1/listener", "namespace": "/robot1"}
    chatter = next(t for t in graph["topics"] if t["name"] == "/chatter")
    assert chatter["publishers"] == ["/talker"] and chatter["subscribers"] == ["/robot1/listener"]
    assert chatter["action"] is None
    add = next(s for s in graph["services"] if s["name"] == "/add")
    assert add["servers"] == ["/server"] and add["clients"] == ["/client"]
    (fib,) = graph["actions"]
    assert fib == {
        "name": "/fib",
        "types": [FIB],
        "servers": ["/server"],
        "clients": ["/client"],
        "action": None,
    }
    parts = [e for e in graph["topics"] + graph["services"] if e["action"] == "/fib"]
    assert len(parts) == 5
    assert action_of("/a/_action/status") == "/a" and action_of("/a/_action/other") is None
    json.dumps(graph)  # what the page gets


def test_a_service_types_fields_describe_its_form() -> None:
    schema = interface_schema("rcl_interfaces/srv/SetParameters")
    (parameters,) = schema["request"]["fields"]
    assert parameters["kind"] == "sequence" and parameters["bound"] == 0
    value = next(f for f in parameters["item"]["fields"] if f["name"] == "value")
    assert value["kind"] == "message" and value["type"] == "rcl_interfaces/msg/ParameterValue"
    kinds = {f["name"]: f for f in value["fields"]}
    assert kinds["double_value"] == {"name": "double_value", "kind": "base", "type": "float64"}
    assert kinds["integer_array_value"]["item"] == {"kind": "base", "type": "int64"}
    imu = interface_schema("sensor_msgs/msg/Imu")["message"]
    covariance = next(f for f in imu["fields"] if f["name"] == "orientation_covariance")
    assert covariance["kind"] == "array" and covariance["length"] == 9
    log = interface_schema("rcl_interfaces/msg/Log")["message"]
    assert {"name": "WARN", "type": "uint8", "value": 30} in log["constants"]


def test_messages_become_json_whatever_their_containers_are() -> None:
    state = get_message("sensor_msgs/msg/JointState")(name=["a", "b"])
    for container in (
        [1.0, 2.0],
        array.array("d", [1.0, 2.0]),
        np.array([1.0, 2.0]),
    ):
        state.position = container
        assert to_data(state)["position"] == [1.0, 2.0], type(container)
    state.position = array.array("d", range(300))
    assert to_data(state, 4)["position"] == [0.0, 1.0, 2.0, 3.0, "..."]
    assert json.dumps(to_data(state, None))


class Recorder:
    """The hub's ROS side, for a session alone: knows types, records service calls."""

    def __init__(self) -> None:
        self.calls: list[tuple[str, str, Any]] = []

    def definition(self, type_name: str) -> str | None:
        from launchkit.ros.msgs import message_definition

        try:
            return message_definition(type_name)
        except Exception:
            return None

    def call_service(self, service: str, type_name: str, request: Any, reply: Any) -> None:
        self.calls.append((service, type_name, request))
        response = get_message(type_name + "_Response")(success=True, message="done")
        reply(response, None)


def test_the_page_protocol_answers_interfaces_calls_and_the_graph() -> None:
    async def run() -> list[dict[str, Any]]:
        sent: list[str] = []

        async def send(frame: str | bytes) -> None:
            sent.append(str(frame))

        source = Recorder()
        hub = Hub(source)  # type: ignore[arg-type]
        session = PageSession(hub, send, {})
        session.handle(json.dumps({"op": "interface", "type": "std_srvs/srv/SetBool"}))
        session.handle(json.dumps({"op": "interface", "type": "nope"}))
        session.handle(
            json.dumps(
                {
                    "op": "call",
                    "id": 7,
                    "service": "/x",
                    "type": "std_srvs/srv/SetBool",
                    "request": {"data": True},
                }
            )
        )
        session.handle(
            json.dumps(
                {
                    "op": "call",
                    "id": 8,
                    "service": "/x",
                    "type": "std_srvs/srv/SetBool",
                    "request": {"data": "yes"},
                }
            )
        )
        session.handle(json.dumps({"op": "subscribe", "topics": ["/a"], "form": "other"}))
        hub.nodes_changed({"nodes": []})
        session.handle(json.dumps({"op": "graph", "watch": True}))
        hub.nodes_changed({"nodes": [{"name": "/n", "namespace": "/"}]})
        session.handle(json.dumps({"op": "graph", "watch": False}))
        hub.nodes_changed({"nodes": []})
        assert source.calls[0][:2] == ("/x", "std_srvs/srv/SetBool")
        assert source.calls[0][2].data is True and len(source.calls) == 1
        task = asyncio.create_task(session.outbox.run())
        while len(session.outbox):
            await asyncio.sleep(0.01)
        task.cancel()
        return [json.loads(frame) for frame in sent]

    frames = asyncio.run(run())
    # the graph waiting to be sent is replaced by a newer one, not queued behind it
    interface, unknown, reply, refused, bad_form, graph = frames
    assert interface["request"]["fields"] == [{"name": "data", "kind": "base", "type": "bool"}]
    assert interface["response"]["type"] == "std_srvs/srv/SetBool_Response"
    assert unknown == {"op": "interface", "type": "nope", "error": unknown["error"]}
    assert reply == {"op": "reply", "id": 7, "response": {"success": True, "message": "done"}}
    assert refused["id"] == 8 and "request.data" in refused["error"]
    assert bad_form["op"] == "error" and "'form'" in bad_form["message"]
    assert graph == {"op": "graph", "graph": {"nodes": [{"name": "/n", "namespace": "/"}]}}
