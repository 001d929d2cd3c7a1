"""Test vectors of rmw_zenoh 0.2.x's wire format (ROS 2 Jazzy), written from its source.

Source: rmw_zenoh's Jazzy release 0.2.10 (the ros2-gbp/rmw_zenoh-release tag ``upstream/0.2.10``;
paths below are under ``rmw_zenoh_cpp/src/detail/``). Every value here was derived by reading the
function named beside it, not by running launchkit; the GIDs were computed by compiling that
release's own ``simplified_xxhash3.cpp`` (``simplified_XXH3_128bits``) in a scratch harness and
feeding it the token strings below, byte for byte.

launchkit must write exactly these (keys, tokens, QoS strings, GIDs, attachments) and read them
back (``tests/ros/test_rmw_zenoh_conformance.py`` checks both directions).
"""

from __future__ import annotations

STRING = "std_msgs/msg/String"
STRING_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
TWIST = "geometry_msgs/msg/Twist"
TWIST_HASH = "RIHS01_9c45bf16fe0983d80e3cfe750d6835843d265a9a6c46bd2e609fcddde6fb8d2a"
SET_BOOL = "std_srvs/srv/SetBool"
SET_BOOL_HASH = "RIHS01_abe9e4bb6b41b40e6789712c00ec8871923e089af3f667a79992a428cff2da0a"
GET_PARAMETERS = "rcl_interfaces/srv/GetParameters"
GET_PARAMETERS_HASH = "RIHS01_bf9803d5c74cf989a5de3e0c2e99444599a627c7ff75f97b8c05b01003675cbc"

# -- data key expressions ------------------------------------------------------------------------
# liveliness_utils.cpp:TopicInfo::TopicInfo: "<domain>/" + strip_slashes(name) + "/<type>/<hash>";
# the type is the type support's name (rmw_publisher_data.cpp:PublisherData::make,
# message_type_support->get_name(): "pkg::msg::dds_::Name_"); for services
# rmw_service_data.cpp:ServiceData::make / rmw_client_data.cpp:ClientData::make cut the
# response/request type name at rfind("Response_") / rfind("Request_"): "pkg::srv::dds_::Name_".
# (domain, fully qualified name, ROS type name, type hash) -> key
TOPIC_KEYS = [
    (
        (0, "/chatter", STRING, STRING_HASH),
        f"0/chatter/std_msgs::msg::dds_::String_/{STRING_HASH}",
    ),
    (
        (7, "/robot/arm/cmd_vel", TWIST, TWIST_HASH),
        f"7/robot/arm/cmd_vel/geometry_msgs::msg::dds_::Twist_/{TWIST_HASH}",
    ),
    (
        (0, "/set_flag", SET_BOOL, SET_BOOL_HASH),
        f"0/set_flag/std_srvs::srv::dds_::SetBool_/{SET_BOOL_HASH}",
    ),
    (
        (232, "/talker/get_parameters", GET_PARAMETERS, GET_PARAMETERS_HASH),
        f"232/talker/get_parameters/rcl_interfaces::srv::dds_::GetParameters_/{GET_PARAMETERS_HASH}",
    ),
]

# -- QoS strings ---------------------------------------------------------------------------------
# liveliness_utils.cpp:qos_to_keyexpr, applied to the profile after qos.cpp:QoS::best_available_qos
# (which turns depth 0 into 42 whatever the history): "R:D:H,depth:DLs,DLns:LSs,LSns:LV,LLs,LLns",
# every field equal to QoS::default_qos() (RELIABLE 1, VOLATILE 2, KEEP_LAST 1, depth 42, infinite
# durations, AUTOMATIC liveliness 1) left empty; enum fields are rmw's numbers (rmw/types.h).
# ((depth, reliability, durability, history), string); reliability 1 reliable / 2 best effort,
# durability 1 transient local / 2 volatile, history 1 keep last / 2 keep all
QOS_WRITTEN = [
    ((10, 1, 2, 1), "::,10:,:,:,,"),
    ((7, 1, 2, 1), "::,7:,:,:,,"),
    ((42, 1, 2, 1), "::,:,:,:,,"),
    ((0, 1, 2, 1), "::,:,:,:,,"),  # KEEP_LAST depth 0 -> 42 -> left empty
    ((0, 1, 2, 2), "::2,:,:,:,,"),  # KEEP_ALL depth 0 -> 42 -> left empty
    ((1, 1, 1, 1), ":1:,1:,:,:,,"),  # /robot_description, /tf_static
    ((5, 2, 2, 1), "2::,5:,:,:,,"),  # sensor data
    ((1000, 1, 2, 1), "::,1000:,:,:,,"),  # rclpy's qos_profile_parameters
]

# liveliness_utils.cpp:keyexpr_to_qos: split at ":" (at least 6 parts), parts 2-4 at "," (at least
# 2 fields, liveliness at least 3), enum fields looked up in str_to_qos_* (exact decimal strings;
# the liveliness map has 0, 1, 3, 4, 5 but not 2), numbers through str_to_size_t (unsigned
# decimal, nothing after the digits, no overflow); empty fields take the defaults.
# string -> (depth, reliability, durability, history) as read
QOS_ACCEPTED = {
    "::,:,:,:,,": (42, 1, 2, 1),
    "::,10:,:,:,,": (10, 1, 2, 1),
    ":1:,1:,:,:,,": (1, 1, 1, 1),
    "2::,5:,:,:,,": (5, 2, 2, 1),
    "::2,0:,:,:,,": (0, 1, 2, 2),  # what launchkit wrote before: rmw_zenoh reads depth 0
    "4:4:3,1:1,2:3,4:5,6,7": (1, 4, 4, 3),  # BEST_AVAILABLE, UNKNOWN history, every duration set
    "0:0:0,3:,:,:0,,": (3, 1, 2, 1),  # SYSTEM_DEFAULT everywhere (read as the defaults)
    "::,10:,:,:,,:more": (10, 1, 2, 1),  # parts beyond the sixth are ignored
}
QOS_REJECTED = [
    "",
    "::,10:,:,:,",  # liveliness has only 2 fields
    "::,10:,:,:",  # 5 parts
    "::10:,:,:,,",  # history part without ","
    "5::,:,:,:,,",  # reliability 5 is not an rmw value
    "01::,:,:,:,,",  # not the exact decimal string of an enum
    "::,:,:,:2,,",  # liveliness 2 (MANUAL_BY_NODE) is not in rmw_zenoh's map
    "::,x:,:,:,,",  # depth not a number
    "::,-1:,:,:,,",  # negative
    "::,10a:,:,:,,",  # junk after the number
    "::,18446744073709551616:,:,:,,",  # overflows 64 bits
]

# -- liveliness tokens ---------------------------------------------------------------------------
# liveliness_utils.cpp:Entity::Entity (KeyexprIndex order): "@ros2_lv/<domain>/<zid>/<nid>/<id>/
# <kind>/<enclave>/<namespace>/<node>[/<topic>/<type>/<hash>/<qos>]", each name through
# mangle_name ("/" -> "%"; rcl gives "/" for the root namespace and the default enclave, so they
# become "%"); kinds NN MP MS SS SC; a node token has nid == id (rmw_node_data.cpp:NodeData::make).
# zid is zenoh::Id::to_string() (rmw_context_impl_s.cpp), the lowercase hex of the session id.
# (fields, token, gid hex): fields = (domain, zid, nid, id, kind, enclave, namespace, node,
# topic, type, hash, qos string) with topic..qos None for nodes.
ZID_A = "8b20ac2f5a0c4a4bbd9e8a3a6c10e85d"
ZID_B = "3246a6f0c1b2d3e4f5a6b7c8d9e063ac"
TOKENS = [
    (
        (0, ZID_A, "0", "0", "NN", "/", "/", "talker", None, None, None, None),
        f"@ros2_lv/0/{ZID_A}/0/0/NN/%/%/talker",
        "babaaea8656a8e5c63c98a7a5c208d2b",
    ),
    (
        (
            0,
            ZID_A,
            "0",
            "1",
            "MP",
            "/",
            "/",
            "talker",
            "/chatter",
            STRING,
            STRING_HASH,
            "::,7:,:,:,,",
        ),
        f"@ros2_lv/0/{ZID_A}/0/1/MP/%/%/talker/%chatter/std_msgs::msg::dds_::String_/"
        f"{STRING_HASH}/::,7:,:,:,,",
        "c41137f9859fee04646e81be8a4920a9",
    ),
    (
        (7, ZID_B, "3", "3", "NN", "/", "/robot/arm", "driver", None, None, None, None),
        f"@ros2_lv/7/{ZID_B}/3/3/NN/%/%robot%arm/driver",
        "b5838a8d8a709b06f51db386632ec72d",
    ),
    (
        (
            7,
            ZID_B,
            "3",
            "4",
            "MS",
            "/",
            "/robot/arm",
            "driver",
            "/robot/arm/cmd_vel",
            TWIST,
            TWIST_HASH,
            "2::,5:,:,:,,",
        ),
        f"@ros2_lv/7/{ZID_B}/3/4/MS/%/%robot%arm/driver/%robot%arm%cmd_vel/"
        f"geometry_msgs::msg::dds_::Twist_/{TWIST_HASH}/2::,5:,:,:,,",
        "9fb37985ef0bae87116a0e110ecafa26",
    ),
    (
        (
            0,
            ZID_A,
            "0",
            "2",
            "MP",
            "/",
            "/",
            "robot_state_publisher",
            "/robot_description",
            STRING,
            STRING_HASH,
            ":1:,1:,:,:,,",
        ),
        f"@ros2_lv/0/{ZID_A}/0/2/MP/%/%/robot_state_publisher/%robot_description/"
        f"std_msgs::msg::dds_::String_/{STRING_HASH}/:1:,1:,:,:,,",
        "f29ff2fe4b20bac494743d0f035be7a5",
    ),
    (
        (
            0,
            ZID_A,
            "0",
            "5",
            "SS",
            "/",
            "/",
            "talker",
            "/talker/get_parameters",
            GET_PARAMETERS,
            GET_PARAMETERS_HASH,
            "::,1000:,:,:,,",
        ),
        f"@ros2_lv/0/{ZID_A}/0/5/SS/%/%/talker/%talker%get_parameters/"
        f"rcl_interfaces::srv::dds_::GetParameters_/{GET_PARAMETERS_HASH}/::,1000:,:,:,,",
        "ebd4a73d8514a563954feb598cd7c86b",
    ),
    (
        (
            0,
            ZID_A,
            "0",
            "6",
            "SC",
            "/",
            "/",
            "talker",
            "/set_flag",
            SET_BOOL,
            SET_BOOL_HASH,
            "::,10:,:,:,,",
        ),
        f"@ros2_lv/0/{ZID_A}/0/6/SC/%/%/talker/%set_flag/std_srvs::srv::dds_::SetBool_/"
        f"{SET_BOOL_HASH}/::,10:,:,:,,",
        "6bf39ffb3bb8ba8be9334b9e28ba7255",
    ),
    (
        (
            0,
            ZID_A,
            "0",
            "7",
            "MS",
            "/secure",
            "/",
            "talker",
            "/kall",
            STRING,
            STRING_HASH,
            "::2,:,:,:,,",
        ),
        f"@ros2_lv/0/{ZID_A}/0/7/MS/%secure/%/talker/%kall/std_msgs::msg::dds_::String_/"
        f"{STRING_HASH}/::2,:,:,:,,",
        "81954ebd4d3617dbb2dcad20ac2f3e75",
    ),
]

# liveliness_utils.cpp:Entity::make(keyexpr) accepts any non-empty nid/id text, and rejects:
TOKENS_REJECTED = [
    f"@ros2_lv/0/{ZID_A}/0/0/NN/%/%",  # fewer than 9 parts
    f"@ros2_lv/0/{ZID_A}/0//NN/%/%/talker",  # an empty part
    f"@ros2_lv/0/{ZID_A}/0/0/XX/%/%/talker",  # unknown kind
    f"@ros2_lv2/0/{ZID_A}/0/0/NN/%/%/talker",  # other admin space
    f"@ros2_lv/0/{ZID_A}/0/1/MP/%/%/talker/%chatter/std_msgs::msg::dds_::String_/{STRING_HASH}",
    f"@ros2_lv/0/{ZID_A}/0/1/MP/%/%/talker/%chatter/std_msgs::msg::dds_::String_/{STRING_HASH}/"
    "::,7:,:,:,",  # invalid QoS string
]
# ... and accepts ids that are not numbers (launchkit must not insist on integers)
TOKEN_WITH_TEXT_IDS = f"@ros2_lv/0/{ZID_A}/n1/e9/NN/%/%/talker"

# -- attachments ---------------------------------------------------------------------------------
# attachment_helpers.cpp:AttachmentData::serialize_to_zbytes (0.2.4 and later): zenoh-ext
# Serializer of int64 sequence number, int64 source timestamp (ns since the epoch, wall clock),
# std::array<uint8_t, 16> GID (a LEB128 length 16, then the bytes). The publisher's sequence
# number starts at 1 (rmw_publisher_data.cpp, sequence_number_(1)); a service reply carries the
# request's sequence number and client GID with a new timestamp (rmw_service_data.cpp:
# ServiceData::send_response).
ATTACHMENT_FIELDS = (1, 1795479698000000000, bytes.fromhex("c41137f9859fee04646e81be8a4920a9"))
ATTACHMENT = bytes.fromhex("01000000000000000034b7c045d3ea1810c41137f9859fee04646e81be8a4920a9")
# upstream/0.2.0 .. 0.2.3 attachment_helpers.cpp wrote labelled values instead: the strings
# "sequence_number", "source_timestamp", "source_gid" (LEB128 length + UTF-8) before each value
LABELLED_ATTACHMENT = (
    b"\x0fsequence_number"
    + bytes.fromhex("0100000000000000")
    + b"\x10source_timestamp"
    + bytes.fromhex("0034b7c045d3ea18")
    + b"\x0asource_gid"
    + b"\x10"
    + bytes.fromhex("c41137f9859fee04646e81be8a4920a9")
)
