"""rviz2's Foxglove relay: real server, real WebSocket client, real CDR from the ROS typestore."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import pytest
from rosbags.typesys import Stores, get_typestore

from launchkit.errors import UserError
from launchkit.stock.rviz2.relay import FoxgloveRelay
from tests.stock.foxglove_client import FoxgloveClient

STORE = get_typestore(Stores.ROS2_JAZZY)
URDF = (Path(__file__).parents[2] / "urdf" / "three_wheeled_robot.urdf").read_text()


def _cdr(type_name: str, **fields: Any) -> bytes:
    return bytes(STORE.serialize_cdr(STORE.types[type_name](**fields), type_name))


def _definition(type_name: str) -> str:
    return str(STORE.generate_msgdef(type_name, ros_version=2)[0])


def _scan() -> bytes:
    import numpy as np

    return _cdr(
        "sensor_msgs/msg/LaserScan",
        header=_header("lidar"),
        angle_min=0.0,
        angle_max=3.14,
        angle_increment=0.0087,
        time_increment=0.0,
        scan_time=0.1,
        range_min=0.1,
        range_max=12.0,
        ranges=np.full(360, 2.5, dtype=np.float32),
        intensities=np.zeros(0, dtype=np.float32),
    )


def _header(frame: str) -> Any:
    time = STORE.types["builtin_interfaces/msg/Time"](sec=1, nanosec=2)
    return STORE.types["std_msgs/msg/Header"](stamp=time, frame_id=frame)


def _tf() -> bytes:
    t = STORE.types
    transform = t["geometry_msgs/msg/TransformStamped"](
        header=_header("base"),
        child_frame_id="wheel_left_link",
        transform=t["geometry_msgs/msg/Transform"](
            translation=t["geometry_msgs/msg/Vector3"](x=0.2, y=-0.25, z=0.0),
            rotation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        ),
    )
    return _cdr("tf2_msgs/msg/TFMessage", transforms=[transform])


@pytest.fixture
def relay() -> Any:
    relay = FoxgloveRelay(port=0)
    yield relay
    relay.close()


def test_late_client_gets_latched_description_then_live_tf_and_scan(relay: FoxgloveRelay) -> None:
    description = _cdr("std_msgs/msg/String", data=URDF)
    relay.add_topic(
        "/robot_description", "std_msgs/msg/String", _definition("std_msgs/msg/String"), True
    )
    relay.publish("/robot_description", description)  # before any client connects
    for topic, type_name in (
        ("/tf", "tf2_msgs/msg/TFMessage"),
        ("/scan", "sensor_msgs/msg/LaserScan"),
    ):
        relay.add_topic(topic, type_name, _definition(type_name), False)
    tf, scan = _tf(), _scan()

    async def session() -> FoxgloveClient:
        async with FoxgloveClient(relay.url) as client:
            await client.subscribe(["/robot_description", "/tf", "/scan"])
            await client.wait_for(
                "the latched /robot_description", lambda: "/robot_description" in client.received
            )
            # live topics reach a client only once its subscription is in place: keep sending
            loop = asyncio.get_running_loop()
            end = loop.time() + 10.0
            while not {"/tf", "/scan"} <= client.received.keys():
                assert loop.time() < end, "timed out waiting for /tf and /scan to reach the client"
                relay.publish("/tf", tf)
                relay.publish("/scan", scan)
                try:
                    await client._handle_one(0.2)
                except asyncio.TimeoutError:
                    pass
            return client

    client = asyncio.run(session())
    channel = client.channels["/scan"]
    assert (channel["encoding"], channel["schemaEncoding"]) == ("cdr", "ros2msg")
    assert channel["schemaName"] == "sensor_msgs/msg/LaserScan"
    assert "float32[] ranges" in channel["schema"]
    assert client.received["/robot_description"][0] == description
    assert (
        STORE.deserialize_cdr(client.received["/robot_description"][0], "std_msgs/msg/String").data
        == URDF
    )
    assert client.received["/tf"][0] == tf
    decoded = STORE.deserialize_cdr(client.received["/scan"][0], "sensor_msgs/msg/LaserScan")
    assert len(decoded.ranges) == 360


def test_busy_port_is_a_user_error(relay: FoxgloveRelay) -> None:
    with pytest.raises(UserError, match=f"127.0.0.1:{relay.port}.*expected a free port"):
        FoxgloveRelay(port=relay.port)
