"""Topics through ``launchkit bridge``: real rclpy (Fast DDS) talkers and listeners against
launchkit nodes, both ways, bytes untouched, QoS mirrored, no echo, topics coming and going."""

from __future__ import annotations

from typing import Any

import pytest
from bridge_helpers import BridgeProcess, DdsPeer, LaunchkitPeer, wait_until
from launchkit.ros.msgs.std_msgs.msg import String

from launchkit.ros import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from launchkit.ros.msgs import serialize

# rclpy's type support imports lark, which imports the deprecated sre_parse
pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")

WAIT = 30.0  # DDS discovery takes 0.25-1.8 s here, more on a loaded machine


def assert_same_payload(received: bytes, sent: bytes) -> None:
    """The same CDR bytes; Fast DDS pads a serialized payload to a multiple of 4 (RTPS), and
    the bridge passes the padded bytes on as it got them."""
    padding = -len(sent) % 4
    assert received == sent + b"\0" * padding, (received, sent)


def _rclpy_string(text: str) -> Any:
    from std_msgs.msg import String as RclpyString

    return RclpyString(data=text)


def test_a_launchkit_talker_reaches_an_rclpy_listener_byte_for_byte(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from std_msgs.msg import String as RclpyString

    raw: list[bytes] = []
    dds.node.create_subscription(RclpyString, "/lk_talk", raw.append, 10, raw=True)
    pub = lk.node.create_publisher(String, "/lk_talk", 10)
    payload = serialize(String(data="héllo from launchkit ✓"), "std_msgs/msg/String")

    def publish() -> bool:
        pub.publish(payload)
        return bool(raw)

    wait_until(publish, WAIT, "launchkit's /lk_talk at an rclpy subscription")
    assert_same_payload(raw[0], payload)
    bridge.wait_line("bridging /lk_talk (std_msgs/msg/String) launchkit -> DDS")


def test_an_rclpy_talker_reaches_a_launchkit_listener_byte_for_byte(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rclpy.serialization import serialize_message
    from std_msgs.msg import String as RclpyString

    raw: list[bytes] = []
    lk.node.create_subscription(String, "/dds_talk", raw.append, 10, raw=True)
    pub = dds.node.create_publisher(RclpyString, "/dds_talk", 10)
    payload = serialize_message(_rclpy_string("hello from rclpy"))

    def publish() -> bool:
        pub.publish(payload)
        return bool(raw)

    wait_until(publish, WAIT, "rclpy's /dds_talk at a launchkit subscription")
    assert_same_payload(raw[0], payload)


def test_a_transient_local_message_reaches_latecomers_on_both_sides(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rclpy.qos import DurabilityPolicy as Durability
    from rclpy.qos import QoSProfile as RclpyQoS
    from std_msgs.msg import String as RclpyString

    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    rclpy_latched = RclpyQoS(depth=1, durability=Durability.TRANSIENT_LOCAL)
    lk.node.create_publisher(String, "/lk_description", latched).publish(
        String(data="<robot name='lk'/>")
    )
    dds.node.create_publisher(RclpyString, "/dds_description", rclpy_latched).publish(
        _rclpy_string("<robot name='dds'/>")
    )
    # both published once, before anyone listened: the bridge must hold them for latecomers
    bridge.wait_line("bridging /lk_description (std_msgs/msg/String) launchkit -> DDS")
    bridge.wait_line("bridging /dds_description (std_msgs/msg/String) DDS -> launchkit")
    bridge.wait_line("transient_local depth 1")
    at_dds: list[str] = []
    at_lk: list[str] = []
    dds.node.create_subscription(
        RclpyString, "/lk_description", lambda m: at_dds.append(m.data), rclpy_latched
    )
    lk.node.create_subscription(String, "/dds_description", lambda m: at_lk.append(m.data), latched)
    wait_until(lambda: bool(at_dds), WAIT, "the latched /lk_description at a late rclpy node")
    wait_until(lambda: bool(at_lk), WAIT, "the latched /dds_description at a late launchkit node")
    assert at_dds == ["<robot name='lk'/>"] and at_lk == ["<robot name='dds'/>"]


def test_qos_is_mirrored_to_the_other_side(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from rclpy.qos import DurabilityPolicy as Durability
    from rclpy.qos import ReliabilityPolicy as Reliability

    lk.node.create_publisher(
        String, "/lk_sensor", QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
    )

    def bridged() -> list[Any]:
        return dds.node.get_publishers_info_by_topic("/lk_sensor")

    # DDS lists an endpoint before the participant's node names arrive on ros_discovery_info
    # (until then rclpy shows _NODE_NAME_UNKNOWN_): wait for both
    def named() -> bool:
        return any(info.node_name != "_NODE_NAME_UNKNOWN_" for info in bridged())

    wait_until(named, WAIT, "the bridge's named DDS publisher of /lk_sensor")
    (info,) = bridged()
    assert info.qos_profile.reliability == Reliability.BEST_EFFORT
    assert info.qos_profile.durability == Durability.VOLATILE
    assert info.node_name == "launchkit_bridge"


def test_nothing_echoes_when_both_sides_publish_and_listen(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    from std_msgs.msg import String as RclpyString

    at_dds: list[str] = []
    at_lk: list[str] = []
    dds.node.create_subscription(RclpyString, "/both", lambda m: at_dds.append(m.data), 100)
    lk.node.create_subscription(String, "/both", lambda m: at_lk.append(m.data), 100)
    dds_pub = dds.node.create_publisher(RclpyString, "/both", 100)
    lk_pub = lk.node.create_publisher(String, "/both", 100)

    def ready(tag: str) -> bool:
        dds_pub.publish(_rclpy_string(f"probe-dds-{tag}"))
        lk_pub.publish(String(data=f"probe-lk-{tag}"))
        probes = [f"probe-dds-{tag}", f"probe-lk-{tag}"]
        return all(p in at_dds for p in probes) and all(p in at_lk for p in probes)

    count = iter(range(10_000))
    wait_until(lambda: ready(str(next(count))), WAIT, "both directions of /both")
    at_dds.clear()
    at_lk.clear()
    for i in range(20):
        dds_pub.publish(_rclpy_string(f"dds-{i}"))
        lk_pub.publish(String(data=f"lk-{i}"))
    expected = sorted([f"dds-{i}" for i in range(20)] + [f"lk-{i}" for i in range(20)])

    def complete(seen: list[str]) -> bool:
        return set(expected) <= {s for s in seen if not s.startswith("probe")}

    wait_until(lambda: complete(at_dds) and complete(at_lk), WAIT, "all 40 messages, both sides")
    # an echo would bring each message back a second time: give echoes the time a message
    # takes to cross twice, then count
    marker = iter(range(10_000))
    wait_until(lambda: ready(f"end-{next(marker)}"), WAIT, "a last round trip")
    for seen in (at_dds, at_lk):
        counted = sorted(s for s in seen if not s.startswith("probe"))
        assert counted == expected, f"duplicates: {sorted(set(counted) - set(expected))}"


def test_a_topic_appears_and_goes_on_the_other_side(
    bridge: BridgeProcess, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    pub = lk.node.create_publisher(String, "/comes_and_goes", 10)
    wait_until(lambda: "/comes_and_goes" in dds.topics(), WAIT, "/comes_and_goes on DDS")
    lk.node.destroy_publisher(pub)
    wait_until(lambda: "/comes_and_goes" not in dds.topics(), WAIT, "/comes_and_goes to go")
    bridge.wait_line("stopped bridging /comes_and_goes launchkit -> DDS")
