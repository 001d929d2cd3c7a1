"""Golden strings of rmw_zenoh's (Jazzy) wire conventions: keys, tokens, QoS, attachments."""

from __future__ import annotations

import pytest
from zenoh import ext

from launchkit.errors import UserError
from launchkit.ros.keyexpr import (
    decode_attachment,
    domain_id,
    encode_attachment,
    entity_token,
    gid_of,
    node_token,
    parse_token,
    topic_key,
)
from launchkit.ros.msgs import type_hash
from launchkit.ros.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

STRING_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"


def test_topic_key() -> None:
    twist = type_hash("geometry_msgs/msg/Twist")
    assert topic_key(0, "/cmd_vel", "geometry_msgs/msg/Twist", twist) == (
        "0/cmd_vel/geometry_msgs::msg::dds_::Twist_/"
        "RIHS01_9c45bf16fe0983d80e3cfe750d6835843d265a9a6c46bd2e609fcddde6fb8d2a"
    )
    assert topic_key(7, "/robot1/cmd_vel", "geometry_msgs/msg/Twist", twist).startswith(
        "7/robot1/cmd_vel/geometry_msgs::msg::dds_::Twist_/"
    )


@pytest.mark.parametrize(
    ("qos", "text"),
    [
        (QoSProfile(depth=10), "::,10:,:,:,,"),
        (QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL), ":1:,1:,:,:,,"),
        (QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT), "2::,5:,:,:,,"),
        (QoSProfile(depth=42), "::,:,:,:,,"),
    ],
)
def test_qos_strings_round_trip(qos: QoSProfile, text: str) -> None:
    assert qos.to_keyexpr() == text
    assert QoSProfile.from_keyexpr(text) == qos


def test_tokens() -> None:
    assert node_token(0, "abc", 1, "/", "/", "talker") == "@ros2_lv/0/abc/1/1/NN/%/%/talker"
    token = entity_token(
        0,
        "abc",
        1,
        2,
        "MP",
        "/",
        "/",
        "talker",
        "/chatter",
        "std_msgs/msg/String",
        STRING_HASH,
        QoSProfile(depth=10),
    )
    assert token == (
        f"@ros2_lv/0/abc/1/2/MP/%/%/talker/%chatter/std_msgs::msg::dds_::String_/"
        f"{STRING_HASH}/::,10:,:,:,,"
    )
    parsed = parse_token(token)
    assert parsed is not None
    assert (parsed.kind, parsed.topic, parsed.type_name, parsed.node_fqn) == (
        "MP",
        "/chatter",
        "std_msgs/msg/String",
        "/talker",
    )
    in_ns = parse_token(node_token(3, "z", 4, "/", "/robot/arm", "driver"))
    assert in_ns is not None and in_ns.node_fqn == "/robot/arm/driver" and in_ns.domain == 3
    assert parse_token("@ros2_lv/0/garbage") is None


def test_attachment_is_zenoh_ext_serialization_of_seq_time_gid() -> None:
    gid = gid_of("@ros2_lv/0/abc/1/2/MP/%/%/talker/%chatter/x/y/z")
    assert len(gid) == 16
    ours = encode_attachment(5, 1_700_000_000_000_000_000, gid)
    theirs = ext.z_serialize((ext.Int64(5), ext.Int64(1_700_000_000_000_000_000), gid))
    assert ours == theirs.to_bytes() and len(ours) == 33
    decoded = decode_attachment(ours)
    assert decoded is not None and (decoded.sequence, decoded.gid) == (5, gid)


def test_labelled_attachment_of_older_jazzy_decodes() -> None:
    gid = bytes(range(16))
    labelled = ext.z_serialize(
        ("sequence_number", ext.Int64(9), "source_timestamp", ext.Int64(11), "source_gid", gid)
    ).to_bytes()
    decoded = decode_attachment(labelled)
    assert decoded is not None and (decoded.sequence, decoded.timestamp_ns, decoded.gid) == (
        9,
        11,
        gid,
    )


def test_domain_id(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_DOMAIN_ID", raising=False)
    assert domain_id() == 0
    monkeypatch.setenv("ROS_DOMAIN_ID", "42")
    assert domain_id() == 42
    monkeypatch.setenv("ROS_DOMAIN_ID", "nope")
    with pytest.raises(UserError):
        domain_id()
