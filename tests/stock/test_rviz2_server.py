"""rviz2's viewer server as a process: HTTP, the Origin and Host checks, both Foxglove
subprotocols, lazy subscriptions, latched topics, client publishing, meshes, the page protocol.

One rviz2 process (with ``--allow-origin http://allowed.example``) serves the whole module; a
probe node in the test process publishes and subscribes on a private router. Each test uses
its own topic names.
"""

from __future__ import annotations

import asyncio
import http.client
import json
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.sensor_msgs.msg import JointState, LaserScan
from launchkit.ros.msgs.std_msgs.msg import String
from websockets.asyncio.client import connect
from websockets.exceptions import InvalidStatus

import launchkit.ros as ros
from launchkit.ros.msgs import deserialize, serialize
from tests.stock.conftest import latched
from tests.stock.foxglove_client import FoxgloveClient
from tests.stock.rviz2_process import DEADLINE, Rviz2, running_rviz2
from tests.support import hosted_router

CONFIG = Path(__file__).parents[2] / "config" / "robot.rviz"  # robot_wheel's
ALLOWED = "http://allowed.example"
PAGE = "launchkit.viewer.v1"


@pytest.fixture(scope="module")
def router_endpoint() -> Iterator[str]:
    """A private router for the module."""
    with hosted_router() as endpoint:
        yield endpoint


@pytest.fixture(scope="module")
def assets(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A package ``meshpkg`` (an ``AMENT_PREFIX_PATH`` prefix) with a mesh, a folder given to
    rviz2 with ``--asset-folder`` with another, and a private folder with a third; each mesh
    is ``meshes/part.stl``."""
    root = tmp_path_factory.mktemp("assets")
    marker = root / "prefix" / "share" / "ament_index" / "resource_index" / "packages" / "meshpkg"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    for folder in (root / "prefix" / "share" / "meshpkg", root / "given", root / "private"):
        (folder / "meshes").mkdir(parents=True)
        (folder / "meshes" / "part.stl").write_bytes(f"solid {folder.name}\n".encode())
    return root


@pytest.fixture(scope="module")
def rviz2(router_endpoint: str, assets: Path) -> Iterator[Rviz2]:
    """rviz2 serving on a free port, allowing one extra origin and one asset folder."""
    with running_rviz2(
        router_endpoint,
        "-d", str(CONFIG), "--allow-origin", ALLOWED, "--asset-folder", str(assets / "given"),
        env={"AMENT_PREFIX_PATH": str(assets / "prefix")},
    ) as rviz2:  # fmt: skip
        yield rviz2


@pytest.fixture(scope="module")
def probe(router_endpoint: str) -> Iterator[Any]:
    """A node of the test process on the module's router."""
    context = ros.Context(router=router_endpoint)
    context.init([])
    node = ros.Node("server_probe", context=context, enable_rosout=False)
    try:
        yield node
    finally:
        node.destroy_node()
        context.shutdown()


def wait_graph(node: Any, predicate: Any, what: str) -> None:
    """Wait (on graph changes) until ``predicate()``; fail naming ``what``."""
    assert node.context.graph.wait_for(predicate, DEADLINE), f"timed out waiting for {what}"


def spin_until(node: Any, predicate: Any, what: str, each: Any = None) -> None:
    """Spin ``node`` until ``predicate()``, calling ``each`` every turn."""
    deadline = time.monotonic() + DEADLINE
    while not predicate():
        assert time.monotonic() < deadline, f"timed out after {DEADLINE} s waiting for {what}"
        if each is not None:
            each()
        ros.spin_once(node, timeout_sec=0.05)


async def keep_publishing(publisher: Any, message: Any, stop: asyncio.Event) -> None:
    """Publish ``message`` every 50 ms until ``stop``."""
    while not stop.is_set():
        publisher.publish(message)
        await asyncio.sleep(0.05)


# -- HTTP and access ---------------------------------------------------------------------------


def test_the_page_and_its_libraries_are_served_over_http(rviz2: Rviz2) -> None:
    status, headers, body = rviz2.get("/")
    assert status == 200 and headers["Content-Type"].startswith("text/html")
    assert b'type="importmap"' in body and b"js/main.js" in body
    assert headers["X-Frame-Options"] == "DENY"
    status, headers, body = rviz2.get("/vendor/three/three.module.js")
    assert status == 200 and headers["Content-Type"].startswith("text/javascript")
    assert len(body) > 100_000
    assert rviz2.get("/vendor/three/three.module.js")[1]["ETag"] == headers["ETag"]
    for missing in ("/nothing.js", "/../cli.py", "/js/../../node.py", "/%2e%2e/node.py"):
        assert rviz2.get(missing)[0] == 404, missing


def test_a_request_for_another_host_name_is_refused(rviz2: Rviz2) -> None:
    """DNS rebinding: a site whose name resolves to 127.0.0.1 gets nothing."""
    assert rviz2.get("/", host=f"evil.example:{rviz2.port}")[0] == 403
    assert rviz2.get("/", host=f"localhost:{rviz2.port}")[0] == 200


@pytest.mark.parametrize(
    ("origin", "accepted"),
    [
        (None, True),  # a program, not a web page
        ("http://127.0.0.1:3000", True),
        ("http://localhost", True),
        ("http://[::1]:8080", True),
        (ALLOWED, True),  # --allow-origin
        ("http://evil.example", False),
        ("https://app.foxglove.dev", False),
        ("null", False),
    ],
)
def test_websocket_origins_other_than_this_machines_are_refused(
    rviz2: Rviz2, origin: str | None, accepted: bool
) -> None:
    async def handshake() -> str | None:
        try:
            async with connect(rviz2.ws, subprotocols=[PAGE], origin=origin) as ws:  # type: ignore[list-item,arg-type]
                hello = json.loads(await asyncio.wait_for(ws.recv(), DEADLINE))
                return str(hello["op"])
        except InvalidStatus as refused:
            assert refused.response.status_code == 403
            return None

    assert (asyncio.run(handshake()) == "hello") is accepted
    if not accepted:
        rviz2.wait_line(f"refused a WebSocket from a page of {origin}")


# -- Foxglove ----------------------------------------------------------------------------------


@pytest.mark.parametrize("subprotocol", ["foxglove.websocket.v1", "foxglove.sdk.v1"])
def test_both_foxglove_subprotocols_are_served(rviz2: Rviz2, probe: Any, subprotocol: str) -> None:
    topic = f"/advertised_{subprotocol.split('.')[1]}"
    probe.create_publisher(String, topic, 10)

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(rviz2.ws, subprotocol) as client:
            assert client.ws.subprotocol == subprotocol
            await client.wait_for(f"{topic} advertised", lambda: topic in client.channels)
            return client

    client = asyncio.run(session())
    assert {"clientPublish", "assets"} <= set(client.server_info["capabilities"])
    assert client.server_info["metadata"]["ROS_DISTRO"] == "jazzy"
    channel = client.channels[topic]
    assert (channel["encoding"], channel["schemaEncoding"]) == ("cdr", "ros2msg")
    assert channel["schemaName"] == "std_msgs/msg/String" and "string data" in channel["schema"]


def test_a_topic_is_subscribed_only_while_a_client_wants_it(rviz2: Rviz2, probe: Any) -> None:
    topic, barrier = "/lazy_scan", "/lazy_barrier"
    publisher = probe.create_publisher(LaserScan, topic, ros.qos_profile_sensor_data)
    barrier_publisher = probe.create_publisher(String, barrier, 10)
    scan = LaserScan(ranges=[1.5] * 90, range_max=10.0)

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(rviz2.ws) as client:
            await client.wait_for(
                "both topics advertised", lambda: {topic, barrier} <= client.channels.keys()
            )
            # rviz2's subscription to the barrier comes after it saw both topics; once the
            # barrier's subscription reaches this process, one to the scan would have too
            await client.subscribe([barrier])
            wait_graph(probe, lambda: barrier_publisher.get_subscription_count() == 1, "barrier")
            assert publisher.get_subscription_count() == 0, "subscribed with nobody watching"
            await client.subscribe([topic])
            stop = asyncio.Event()
            sender = asyncio.create_task(keep_publishing(publisher, scan, stop))
            await client.wait_for(f"a message on {topic}", lambda: topic in client.received)
            wait_graph(probe, lambda: publisher.get_subscription_count() == 1, "one subscription")
            await client.unsubscribe([topic])
            stop.set()
            await sender
            wait_graph(probe, lambda: publisher.get_subscription_count() == 0, "unsubscribe")
            return client

    client = asyncio.run(session())
    decoded = deserialize(client.received[topic][0], "sensor_msgs/msg/LaserScan")
    assert len(decoded.ranges) == 90


def test_latched_topics_reach_every_late_client(rviz2: Rviz2, probe: Any) -> None:
    topic = "/late_description"
    description = probe.create_publisher(String, topic, latched())
    description.publish(String(data="<robot name='late'/>"))

    async def one_client() -> bytes:
        async with FoxgloveClient(rviz2.ws) as client:
            await client.wait_for(f"{topic} advertised", lambda: topic in client.channels)
            await client.subscribe([topic])
            await client.wait_for(f"the latched {topic}", lambda: topic in client.received)
            return client.received[topic][0]

    async def two_clients() -> list[bytes]:
        first = await one_client()
        async with FoxgloveClient(rviz2.ws) as holder:  # keeps the ROS subscription alive
            await holder.wait_for(f"{topic} advertised", lambda: topic in holder.channels)
            await holder.subscribe([topic])
            await holder.wait_for("the holder's copy", lambda: topic in holder.received)
            second = await one_client()  # served from the kept history
        return [first, second]

    for payload in asyncio.run(two_clients()):
        assert deserialize(payload, "std_msgs/msg/String").data == "<robot name='late'/>"


@pytest.mark.parametrize("encoding", ["cdr", "json"])
def test_client_publish_drives_the_robot(rviz2: Rviz2, probe: Any, encoding: str) -> None:
    """What Foxglove's teleop panel does: advertise /cmd_vel, send Twists."""
    topic = f"/cmd_vel_{encoding}"
    received: list[Any] = []
    probe.create_subscription(Twist, topic, received.append, 10)
    twist = Twist(linear=Vector3(x=0.5), angular=Vector3(z=-0.25))
    payload = (
        serialize(twist)
        if encoding == "cdr"
        else json.dumps({"linear": {"x": 0.5}, "angular": {"z": -0.25}}).encode()
    )

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(rviz2.ws) as client:
            await client.send_json(
                {
                    "op": "advertise",
                    "channels": [
                        {
                            "id": 7,
                            "topic": topic,
                            "encoding": encoding,
                            "schemaName": "geometry_msgs/Twist",
                        }
                    ],
                }
            )
            await client.ws.send(b"\x01" + (9).to_bytes(4, "little") + payload)  # not advertised
            await client.ws.send(b"\x01" + (7).to_bytes(4, "little") + b"\x00\x01")  # not a Twist
            await client.wait_for("two error statuses", lambda: len(client.statuses) >= 2)
            loop = asyncio.get_running_loop()
            end = loop.time() + DEADLINE
            while not received:
                assert loop.time() < end, f"timed out waiting for the Twist on {topic}"
                await client.ws.send(b"\x01" + (7).to_bytes(4, "little") + payload)
                await asyncio.to_thread(ros.spin_once, probe, timeout_sec=0.1)
            return client

    client = asyncio.run(session())
    assert (received[0].linear.x, received[0].angular.z) == (0.5, -0.25)
    assert "client channel 9, which is not advertised" in client.statuses[0]["message"]
    assert "not a valid geometry_msgs/msg/Twist" in client.statuses[1]["message"]


def test_meshes_the_description_names_are_served_and_nothing_else(
    rviz2: Rviz2, probe: Any, assets: Path
) -> None:
    mesh = assets / "given" / "meshes" / "part.stl"
    (mesh.parent / "secret.stl").write_bytes(b"not named by the robot")
    urdf = (
        f"<robot name='meshy'><link name='base'><visual><geometry>"
        f"<mesh filename='file://{mesh}'/></geometry></visual></link></robot>"
    )
    topic = "/mesh_description"
    probe.create_publisher(String, topic, latched()).publish(String(data=urdf))
    asset = f"/asset/file{mesh}"
    assert rviz2.get(asset)[0] == 404, "served before any robot description named it"

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(rviz2.ws) as client:
            await client.wait_for(f"{topic} advertised", lambda: topic in client.channels)
            await client.subscribe([topic])
            await client.wait_for("the description", lambda: topic in client.received)
            secret = f"file://{mesh.parent}/secret.stl"
            for request_id, uri in ((1, f"file://{mesh}"), (2, secret)):
                await client.send_json({"op": "fetchAsset", "uri": uri, "requestId": request_id})
            await client.wait_for("two asset responses", lambda: len(client.binary) >= 2)
            return client

    client = asyncio.run(session())
    status, headers, body = rviz2.get(asset)
    assert (status, body) == (200, mesh.read_bytes())
    assert headers["Content-Type"] == "model/stl"
    assert rviz2.get(f"/asset/file{mesh.parent}/secret.stl")[0] == 404
    assert rviz2.get("/asset/file/etc/passwd")[0] == 404
    found, refused = sorted(client.binary, key=lambda b: int.from_bytes(b[1:5], "little"))
    assert found[5] == 0 and found.endswith(mesh.read_bytes())
    assert refused[5] == 1 and b"not a file the robot description names" in refused


def test_a_description_from_the_network_reaches_only_trusted_folders(
    rviz2: Rviz2, probe: Any, assets: Path
) -> None:
    # Any graph member may publish a description: naming a file makes it reachable only inside
    # the package share folders and the folders rviz2 was given.
    share = assets / "prefix" / "share" / "meshpkg" / "meshes" / "part.stl"
    private = assets / "private" / "meshes" / "part.stl"
    escape = "package://meshpkg/../../../private/meshes/part.stl"
    names = ["package://meshpkg/meshes/part.stl", f"file://{share}", f"file://{private}", escape]
    meshes = "".join(f"<visual><geometry><mesh filename='{n}'/></geometry></visual>" for n in names)
    urdf = f"<robot name='foreign'><link name='base'>{meshes}</link></robot>"
    topic = "/foreign_description"
    probe.create_publisher(String, topic, latched()).publish(String(data=urdf))

    async def session() -> None:
        async with FoxgloveClient(rviz2.ws) as client:
            await client.wait_for(f"{topic} advertised", lambda: topic in client.channels)
            await client.subscribe([topic])
            await client.wait_for("the description", lambda: topic in client.received)

    asyncio.run(session())
    assert rviz2.get("/asset/package/meshpkg/meshes/part.stl")[:3:2] == (200, share.read_bytes())
    assert rviz2.get(f"/asset/file{share}")[0] == 200
    assert rviz2.get(f"/asset/file{private}")[0] == 404
    assert rviz2.get("/asset/package/meshpkg/../../../private/meshes/part.stl")[0] == 404


def test_bad_requests_are_refused_cleanly(rviz2: Rviz2) -> None:
    connection = http.client.HTTPConnection("127.0.0.1", rviz2.port, timeout=10)
    try:
        connection.putrequest("GET", "/", skip_host=True)
        connection.putheader("Host", f"127.0.0.1:{rviz2.port}")
        connection.putheader("Host", "elsewhere.example")
        connection.endheaders()
        response = connection.getresponse()
        assert (response.status, response.read()) == (400, b"more than one Host header\n")
    finally:
        connection.close()
    assert rviz2.get("/asset/file/a%00b.stl")[0] == 404

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(rviz2.ws) as client:
            channel = {"id": 1, "topic": "/in valid", "encoding": "cdr"}
            channel["schemaName"] = "std_msgs/msg/String"
            await client.send_json({"op": "advertise", "channels": [channel]})
            await client.send_json({"op": "fetchAsset", "uri": "file:///a\u0000b", "requestId": 7})
            await client.wait_for("an asset response", lambda: len(client.binary) >= 1)
            await client.wait_for("a status", lambda: len(client.statuses) >= 1)
            return client

    client = asyncio.run(session())
    assert "invalid topic name '/in valid'" in client.statuses[0]["message"]
    assert client.binary[0][5] == 1  # an error response, the connection still open
    assert not [line for line in rviz2.lines if "Traceback" in line], rviz2.lines


# -- the page's protocol -----------------------------------------------------------------------


def test_the_page_protocol_converts_messages_and_publishes(rviz2: Rviz2, probe: Any) -> None:
    scan_topic, cmd_topic, sliders = "/page_scan", "/page_cmd_vel", "/gui/slider_positions"
    scan_pub = probe.create_publisher(LaserScan, scan_topic, 10)
    scan = LaserScan(ranges=[1.0, float("inf"), 2.5], range_min=0.1, range_max=10.0)
    scan.header.frame_id = "lidar"
    twists: list[Any] = []
    probe.create_subscription(Twist, cmd_topic, twists.append, 10)
    probe.create_subscription(JointState, sliders, lambda m: None, 10)

    async def session() -> dict[str, Any]:
        async with connect(rviz2.ws, subprotocols=[PAGE]) as ws:  # type: ignore[list-item]
            got: dict[str, Any] = {}
            stop = asyncio.Event()
            sender: asyncio.Task[None] | None = None
            loop = asyncio.get_running_loop()
            end = loop.time() + DEADLINE
            while not {"hello", "sliders", "msg", "rates"} <= got.keys() or not twists:
                assert loop.time() < end, f"timed out; got {sorted(got)}, twists {len(twists)}"
                try:
                    message = json.loads(await asyncio.wait_for(ws.recv(), 0.2))
                except asyncio.TimeoutError:
                    message = {}
                op = message.get("op")
                if op == "sliders" and message["topic"] != sliders:
                    continue  # the slider topic is not in the graph yet
                if op:
                    got[op] = message
                if op == "topics" and scan_topic in {t["name"] for t in message["topics"]}:
                    if sender is None:
                        await ws.send(json.dumps({"op": "subscribe", "topics": [scan_topic]}))
                        sender = asyncio.create_task(keep_publishing(scan_pub, scan, stop))
                if "msg" in got:
                    await ws.send(
                        json.dumps(
                            {
                                "op": "publish",
                                "topic": cmd_topic,
                                "type": "geometry_msgs/msg/Twist",
                                "msg": {"linear": {"x": 0.3}},
                            }
                        )
                    )
                    await asyncio.to_thread(ros.spin_once, probe, timeout_sec=0.05)
            await ws.send(json.dumps({"op": "publish", "topic": "/x", "type": "nope/Nope"}))
            while "error" not in got:
                message = json.loads(await asyncio.wait_for(ws.recv(), DEADLINE))
                got[message["op"]] = message
            stop.set()
            if sender is not None:
                await sender
            return got

    got = asyncio.run(session())
    assert got["hello"]["config"]["fixedFrame"] == "odom"
    assert "LaserScan" in {d["class"] for d in got["hello"]["config"]["displays"]}
    assert got["sliders"]["topic"] == sliders
    msg = got["msg"]["msg"]
    assert (got["msg"]["topic"], msg["frame"], msg["ranges"]) == (
        scan_topic,
        "lidar",
        [1.0, None, 2.5],
    )
    assert scan_topic in got["rates"]["rates"]
    assert twists[0].linear.x == 0.3
    assert "unknown type nope/msg/Nope" in got["error"]["message"]
