"""launchkit against rmw_zenoh 0.2.x's wire format, both ways (vectors: rmw_zenoh_vectors.py).

Written: launchkit's keys, tokens, QoS strings, GIDs and attachments are the vectors' bytes, and
a live node announces what rmw_zenoh would for the same entities. Read: launchkit parses what
rmw_zenoh writes (and rejects what it rejects), and a raw Zenoh peer speaking rmw_zenoh's format
reaches launchkit's subscriptions and services.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import pytest
import zenoh
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.std_srvs.srv import SetBool
from rmw_zenoh_vectors import (
    ATTACHMENT,
    ATTACHMENT_FIELDS,
    LABELLED_ATTACHMENT,
    QOS_ACCEPTED,
    QOS_REJECTED,
    QOS_WRITTEN,
    STRING,
    TOKEN_WITH_TEXT_IDS,
    TOKENS,
    TOKENS_REJECTED,
    TOPIC_KEYS,
)
from ros_helpers import spin_until
from zenoh import ext

from launchkit.errors import UserError
from launchkit.ros import DurabilityPolicy, HistoryPolicy, Node, QoSProfile, ReliabilityPolicy
from launchkit.ros.context import Context
from launchkit.ros.graph import snapshot
from launchkit.ros.keyexpr import (
    decode_attachment,
    encode_attachment,
    entity_token,
    gid_of,
    node_token,
    parse_token,
    topic_key,
)
from launchkit.ros.msgs import serialize
from launchkit.ros.session import close_session, open_session, peer_config

# the vectors' topic and service keys are those of ROS domain 0
VECTORS_DOMAIN = 0


def _profile(fields: tuple[int, int, int, int]) -> QoSProfile:
    depth, reliability, durability, history = fields
    return QoSProfile(
        depth=depth,
        reliability=ReliabilityPolicy(reliability),
        durability=DurabilityPolicy(durability),
        history=HistoryPolicy(history),
    )


@pytest.mark.parametrize(("args", "key"), TOPIC_KEYS)
def test_topic_keys_are_rmw_zenohs(args: tuple[int, str, str, str], key: str) -> None:
    assert topic_key(*args) == key


@pytest.mark.parametrize(("fields", "text"), QOS_WRITTEN)
def test_qos_strings_are_written_as_rmw_zenoh_writes_them(
    fields: tuple[int, int, int, int], text: str
) -> None:
    assert _profile(fields).to_keyexpr() == text


@pytest.mark.parametrize(("text", "fields"), list(QOS_ACCEPTED.items()))
def test_qos_strings_rmw_zenoh_accepts_are_read(
    text: str, fields: tuple[int, int, int, int]
) -> None:
    assert QoSProfile.from_keyexpr(text) == _profile(fields)


@pytest.mark.parametrize("text", QOS_REJECTED)
def test_qos_strings_rmw_zenoh_rejects_are_rejected(text: str) -> None:
    with pytest.raises(UserError):
        QoSProfile.from_keyexpr(text)


@pytest.mark.parametrize(("fields", "token", "gid"), TOKENS)
def test_tokens_and_gids_are_written_as_rmw_zenoh_writes_them(
    fields: tuple[object, ...], token: str, gid: str
) -> None:
    domain, zid, nid, eid, kind, enclave, namespace, node, topic, type_name, hash_, qos = fields
    assert isinstance(domain, int) and isinstance(zid, str) and isinstance(nid, str)
    assert isinstance(eid, str) and isinstance(kind, str) and isinstance(node, str)
    assert isinstance(enclave, str) and isinstance(namespace, str)
    if kind == "NN":
        written = node_token(domain, zid, int(nid), enclave, namespace, node)
    else:
        assert isinstance(topic, str) and isinstance(type_name, str) and isinstance(hash_, str)
        assert isinstance(qos, str)
        profile = QoSProfile.from_keyexpr(qos)
        written = entity_token(
            domain, zid, int(nid), int(eid), kind, enclave, namespace, node, topic, type_name,
            hash_, profile,
        )  # fmt: skip
    assert written == token
    assert gid_of(token).hex() == gid


@pytest.mark.parametrize(("fields", "token", "gid"), TOKENS)
def test_tokens_rmw_zenoh_writes_are_read(fields: tuple[object, ...], token: str, gid: str) -> None:
    domain, zid, nid, eid, kind, enclave, namespace, node, topic, type_name, hash_, qos = fields
    parsed = parse_token(token)
    assert parsed is not None
    assert (parsed.domain, parsed.zid, parsed.node_id, parsed.entity_id, parsed.kind) == (
        domain,
        zid,
        nid,
        eid,
        kind,
    )
    assert (parsed.enclave, parsed.namespace, parsed.node_name) == (enclave, namespace, node)
    if kind != "NN":
        assert (parsed.topic, parsed.type_name, parsed.type_hash) == (topic, type_name, hash_)
        assert parsed.qos is not None and parsed.qos.to_keyexpr() == qos
    assert parsed.gid.hex() == gid


@pytest.mark.parametrize("token", TOKENS_REJECTED)
def test_tokens_rmw_zenoh_rejects_are_rejected(token: str) -> None:
    assert parse_token(token) is None


def test_token_ids_need_not_be_numbers() -> None:
    parsed = parse_token(TOKEN_WITH_TEXT_IDS)
    assert parsed is not None and (parsed.node_id, parsed.entity_id) == ("n1", "e9")


def test_attachments_are_rmw_zenohs_both_ways() -> None:
    sequence, stamp, gid = ATTACHMENT_FIELDS
    assert encode_attachment(sequence, stamp, gid) == ATTACHMENT
    # zenoh's own serializer (the one rmw_zenoh's zenoh::ext::Serializer mirrors) agrees
    assert ext.z_serialize((ext.Int64(sequence), ext.Int64(stamp), gid)).to_bytes() == ATTACHMENT
    for data in (ATTACHMENT, LABELLED_ATTACHMENT):
        decoded = decode_attachment(data)
        assert decoded is not None
        assert (decoded.sequence, decoded.timestamp_ns, decoded.gid) == ATTACHMENT_FIELDS


# -- live: a launchkit node on the wire, and a raw peer speaking rmw_zenoh's format --------------


def _tokens_of(node: Node, context: Context, count: int) -> dict[str, str]:
    """topic or node name + kind -> QoS string of ``node``'s tokens, once ``count`` are seen."""
    own = str(node.context.session.zid())
    deadline = time.monotonic() + 10
    while True:
        tokens = [t for t in snapshot(context.session, context.domain_id) if t.zid == own]
        if len(tokens) >= count or time.monotonic() > deadline:
            break
        time.sleep(0.02)
    for token in tokens:  # every token re-emits byte for byte through rmw_zenoh's grammar
        assert token.qos is None or token.key.endswith("/" + token.qos.to_keyexpr())
    return {f"{t.kind} {t.topic or t.node_name}": t.key.rsplit("/", 1)[1] for t in tokens}


def test_a_live_node_announces_what_rmw_zenoh_would(contexts: Callable[[], Context]) -> None:
    node = Node("talker", context=contexts())
    node.create_subscription(
        String, "kall", lambda m: None, QoSProfile(depth=0, history=HistoryPolicy.KEEP_ALL)
    )
    node.create_service(SetBool, "set_flag", lambda q, r: r, qos_profile=QoSProfile(depth=5))
    node.create_client(SetBool, "/other", qos_profile=QoSProfile(depth=3))
    # NN + 6 parameter services + the 3 entities above
    seen = _tokens_of(node, contexts(), 10)
    assert seen["NN talker"] == "talker"
    assert seen["MS /kall"] == "::2,:,:,:,,"  # depth 0 written as rmw_zenoh does (42: empty)
    assert seen["SS /set_flag"] == "::,5:,:,:,,"  # create_service honours its QoS
    assert seen["SC /other"] == "::,3:,:,:,,"  # create_client too
    for name in ("get_parameters", "set_parameters", "list_parameters"):
        assert seen[f"SS /talker/{name}"] == "::,1000:,:,:,,"  # rclpy's qos_profile_parameters


@pytest.fixture
def raw_peer(router: str) -> zenoh.Session:
    """A bare Zenoh peer on the test's router (it speaks rmw_zenoh's format by hand)."""
    session = open_session(peer_config(router))
    yield session
    close_session(session)


def test_a_sample_written_as_rmw_zenoh_writes_it_is_received(
    contexts: Callable[[], Context], raw_peer: zenoh.Session
) -> None:
    node = Node("listener", context=contexts(domain=VECTORS_DOMAIN))
    got: list[tuple[str, dict[str, object]]] = []
    node.create_subscription(String, "/chatter", lambda m, info: got.append((m.data, info)), 10)
    ((key_args, key),) = [v for v in TOPIC_KEYS if v[0][1] == "/chatter"]
    assert key_args[2] == STRING
    publisher = raw_peer.declare_publisher(key)
    payload = serialize(String(data="from an rmw_zenoh peer"), STRING)

    def put() -> bool:
        publisher.put(payload, attachment=ATTACHMENT)
        return bool(got)

    spin_until(node, put, 10, "a sample put on rmw_zenoh's key with its attachment")
    data, info = got[0]
    sequence, stamp, gid = ATTACHMENT_FIELDS
    assert data == "from an rmw_zenoh peer"
    assert info["publisher_gid"] == gid
    assert (info["publication_sequence_number"], info["source_timestamp"]) == (sequence, stamp)
    publisher.undeclare()


def test_a_service_answers_an_rmw_zenoh_request_with_its_sequence_and_gid(
    contexts: Callable[[], Context], raw_peer: zenoh.Session
) -> None:
    node = Node("server", context=contexts(domain=VECTORS_DOMAIN))
    node.create_service(
        SetBool, "/set_flag", lambda q, r: SetBool.Response(success=q.data, message="ok")
    )
    stop = threading.Event()
    spinner = threading.Thread(target=lambda: _spin(node, stop), daemon=True)
    spinner.start()
    ((_, key),) = [v for v in TOPIC_KEYS if v[0][1] == "/set_flag"]
    request = serialize(SetBool.Request(data=True), "std_srvs/srv/SetBool_Request")
    sequence, _, gid = ATTACHMENT_FIELDS
    replies: list[zenoh.Reply] = []
    deadline = time.monotonic() + 10
    try:
        while not replies and time.monotonic() < deadline:
            replies = list(
                raw_peer.get(
                    key,
                    payload=request,
                    attachment=encode_attachment(5, time.time_ns(), gid),
                    target=zenoh.QueryTarget.ALL_COMPLETE,
                    timeout=2.0,
                )
            )
    finally:
        stop.set()
        spinner.join(5)
    assert replies, "no reply to a request on rmw_zenoh's service key"
    ok = replies[0].ok
    assert ok is not None and ok.attachment is not None
    answer = decode_attachment(ok.attachment.to_bytes())
    assert answer is not None and (answer.sequence, answer.gid) == (5, gid)
    assert sequence == 1  # (the vector's own sequence is the publisher's first)
    assert ok.payload.to_bytes()[4] == 1  # success: true


def _spin(node: Node, stop: threading.Event) -> None:
    from launchkit.ros import spin_once

    while not stop.is_set():
        spin_once(node, timeout_sec=0.05)
