"""What the bridge decides to carry, from both graphs (pure: no processes)."""

from __future__ import annotations

import pytest

from launchkit.bridge.echo_guard import DdsWrites
from launchkit.bridge.graph_view import GraphView, ServiceEnds, TopicEnds, zenoh_view
from launchkit.bridge.plan import DDS, ZENOH, FilterError, NameFilter, mirrored_qos, plan
from launchkit.ros import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from launchkit.ros.keyexpr import entity_token, node_token, parse_token

STRING = "std_msgs/msg/String"
LATCHED = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
SENSOR = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)


def _side(**topics: TopicEnds) -> GraphView:
    return GraphView(topics={"/" + k: v for k, v in topics.items()})


def test_a_published_topic_is_bridged_and_subscribed_only_while_the_other_side_listens() -> None:
    zenoh = _side(odom=TopicEnds({"nav_msgs/msg/Odometry"}, [QoSProfile(depth=10)]))
    quiet = plan(zenoh, GraphView(), NameFilter())
    (route,) = quiet.topics.values()
    assert (route.topic, route.source, route.active) == ("/odom", ZENOH, False)
    listening = plan(zenoh, _side(odom=TopicEnds({"nav_msgs/msg/Odometry"}, [], 1)), NameFilter())
    assert listening.topics[(ZENOH, "/odom")].active


def test_transient_local_topics_are_always_subscribed_for_latecomers() -> None:
    dds = _side(tf_static=TopicEnds({"tf2_msgs/msg/TFMessage"}, [LATCHED]))
    (route,) = plan(GraphView(), dds, NameFilter()).topics.values()
    assert route.source == DDS and route.active and route.qos == LATCHED


def test_both_sides_publishing_bridge_both_ways() -> None:
    ends = TopicEnds({STRING}, [QoSProfile(depth=10)], 1)
    routes = plan(_side(chatter=ends), _side(chatter=ends), NameFilter()).topics
    assert set(routes) == {(ZENOH, "/chatter"), (DDS, "/chatter")}


def test_mirrored_qos_is_what_every_publisher_can_feed() -> None:
    assert mirrored_qos([LATCHED]) == LATCHED
    mixed = mirrored_qos([LATCHED, SENSOR, QoSProfile(depth=0)])
    assert mixed.reliability == ReliabilityPolicy.BEST_EFFORT  # one best-effort writer
    assert mixed.durability == DurabilityPolicy.VOLATILE  # one volatile writer
    assert mixed.depth == 42  # depth 0 is rmw_zenoh's 42, the deepest


def test_a_topic_with_two_types_is_skipped_with_the_reason() -> None:
    zenoh = _side(x=TopicEnds({STRING}, [QoSProfile(depth=10)]))
    dds = _side(x=TopicEnds({"std_msgs/msg/Int32"}, [], 1))
    result = plan(zenoh, dds, NameFilter())
    assert not result.topics and "more than one type" in result.skipped["/x"]


def test_filters_match_whole_names() -> None:
    names = NameFilter.parse(["/robot/.*", "/odom"], ["/robot/camera.*"])
    assert names.accepts("/robot/scan") and names.accepts("/odom")
    assert not names.accepts("/odometry") and not names.accepts("/robot/camera/image_raw")
    assert NameFilter.parse([], ["/rosout"]).accepts("/chatter")
    with pytest.raises(FilterError, match="--exclude '\\(': "):
        NameFilter.parse([], ["("])


def test_services_go_to_the_side_without_a_server() -> None:
    zenoh = GraphView(services={"/spawn_entity": ServiceEnds({"gazebo_msgs/srv/SpawnEntity"}, 1)})
    dds = GraphView(services={"/flag": ServiceEnds({"std_srvs/srv/SetBool"}, 1)})
    result = plan(zenoh, dds, NameFilter())
    assert set(result.services) == {(ZENOH, "/spawn_entity"), (DDS, "/flag")}
    both = plan(zenoh, GraphView(services=dict(zenoh.services)), NameFilter())
    assert not both.services  # real servers on both sides: each side keeps its own
    assert not plan(zenoh, dds, NameFilter(), bridge_services=False).services


def test_the_bridges_own_launchkit_entities_are_not_in_its_view() -> None:
    def token(zid: str, kind: str) -> str:
        return entity_token(0, zid, 1, 2, kind, "/", "/", "n", "/t", STRING, "RIHS01_x", LATCHED)

    keys = [node_token(0, "own", 1, "/", "/", "n"), token("own", "MP"), token("other", "MS")]
    view = zenoh_view([t for t in map(parse_token, keys) if t is not None], "own")
    assert view.topics["/t"].publishers == [] and view.topics["/t"].subscriptions == 1


def test_own_dds_writes_are_recognised_and_nothing_else() -> None:
    writes = DdsWrites()
    sent: list[bytes] = []
    writes.write(b"first", sent.append)
    writes.write(b"second", sent.append)
    assert sent == [b"first", b"second"]
    # what Fast DDS reports for our second write comes back: sequence 2, stamp inside the write
    import time

    now = time.time_ns()
    assert not writes.is_own(b"second", {"publication_sequence_number": 2, "source_timestamp": now})
    (_digest, _length, before, _after) = writes._writes[2]
    own = {"publication_sequence_number": 2, "source_timestamp": before}
    assert writes.is_own(b"second", own)
    assert writes.is_own(b"second\0\0", own)  # as Fast DDS pads it to a multiple of 4
    assert not writes.is_own(b"second\0\0\0\0", own)
    assert not writes.is_own(b"other bytes", own)  # another writer's 2nd sample
    assert not writes.is_own(b"second", {**own, "publication_sequence_number": 3})
