"""``launchkit node|interface|pkg|doctor ...``, compared with what ``ros2 node``, ``ros2
interface``, ``ros2 pkg`` and ``ros2 doctor`` print (ros2cli, Jazzy)."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from cli_helpers import graph_of, launchkit
from ros_helpers import Child

from launchkit.testing._isolation import free_loopback_port, router_endpoint

SECTIONS = (
    "Subscribers",
    "Publishers",
    "Service Servers",
    "Service Clients",
    "Action Servers",
    "Action Clients",
)


@pytest.fixture(scope="module")
def graph() -> Iterator[list[Child]]:
    """/knobs, and the graph of an action server /fib_server and client /fib_client."""
    with graph_of("knobs", "action_graph") as children:
        yield children


def sections(text: str) -> dict[str, list[str]]:
    """``node info``'s sections by title: their lines."""
    found: dict[str, list[str]] = {}
    current = ""
    for line in text.splitlines()[1:]:
        if line.startswith("  ") and not line.startswith("    "):
            current = line.strip().rstrip(":")
            found[current] = []
        else:
            found[current].append(line)
    return found


def test_node_list_and_info(graph: list[Child]) -> None:
    listed = launchkit("node", "list").stdout
    assert listed == "/fib_client\n/fib_server\n/knobs\n"
    assert launchkit("node", "list", "-c").stdout == "3\n"

    info = launchkit("node", "info", "/knobs").stdout
    assert info.startswith("/knobs\n")
    parts = sections(info)
    assert list(parts) == list(SECTIONS)
    assert "    /rosout: rcl_interfaces/msg/Log" in parts["Publishers"]
    assert "    /knobs/toggle: std_srvs/srv/SetBool" in parts["Service Servers"]
    assert "    /knobs/get_parameters: rcl_interfaces/srv/GetParameters" in parts["Service Servers"]
    assert parts["Subscribers"] == [""] and parts["Action Servers"] == [""]  # none: one empty line

    # an action server and client, found from the action's topics as rcl_action finds them;
    # the action's own topics and services are hidden names
    assert launchkit("node", "info", "/fib_server").stdout == (
        "/fib_server\n"
        "  Subscribers:\n\n"
        "  Publishers:\n\n"
        "  Service Servers:\n\n"
        "  Service Clients:\n\n"
        "  Action Servers:\n"
        "    /fibonacci: example_interfaces/action/Fibonacci\n"
        "  Action Clients:\n\n"
    )
    client = sections(launchkit("node", "info", "fib_client").stdout)
    assert client["Action Clients"] == ["    /fibonacci: example_interfaces/action/Fibonacci"]
    assert client["Action Servers"] == [""]
    # nodes without parameter services are said so, and the others listed (ros2 param list)
    assert launchkit("param", "list").stdout.startswith(
        "Wait for service timed out waiting for parameter services for node /fib_client\n"
        "Wait for service timed out waiting for parameter services for node /fib_server\n"
        "/knobs:\n  count\n"
    )
    hidden = sections(launchkit("node", "info", "/fib_server", "--include-hidden").stdout)
    assert hidden["Publishers"] == [
        "    /fibonacci/_action/feedback: example_interfaces/action/Fibonacci_FeedbackMessage",
        "    /fibonacci/_action/status: action_msgs/msg/GoalStatusArray",
    ]
    assert hidden["Service Servers"] == [
        "    /fibonacci/_action/cancel_goal: action_msgs/srv/CancelGoal",
        "    /fibonacci/_action/get_result: example_interfaces/action/Fibonacci_GetResult",
        "    /fibonacci/_action/send_goal: example_interfaces/action/Fibonacci_SendGoal",
    ]


def test_node_info_hides_hidden_names_and_nodes_unless_asked() -> None:
    # as ros2 node info: a topic or service with a part starting with "_" is left out, and a
    # hidden node is not found, unless --include-hidden
    with graph_of("hidden_parts"):
        plain = sections(launchkit("node", "info", "/hider").stdout)
        assert plain["Publishers"] == [
            "    /parameter_events: rcl_interfaces/msg/ParameterEvent",
            "    /rosout: rcl_interfaces/msg/Log",
            "    /shown: std_msgs/msg/String",
        ]
        assert not [line for line in plain["Service Servers"] if "/_" in line]
        everything = sections(launchkit("node", "info", "/hider", "--include-hidden").stdout)
        assert "    /_private/state: std_msgs/msg/String" in everything["Publishers"]
        assert "    /hider/_secret: std_srvs/srv/Trigger" in everything["Service Servers"]

        refused = launchkit("node", "info", "/_helper")
        assert refused.returncode == 2 and refused.stdout == ""
        assert refused.stderr == (
            "error: /_helper is a hidden node (expected --include-hidden to show hidden nodes)\n"
        )
        helper = sections(launchkit("node", "info", "/_helper", "--include-hidden").stdout)
        assert helper["Subscribers"] == ["    /shown: std_msgs/msg/String"]


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An ament prefix with package ``my_interfaces``: a message, a service, an action, a
    package.xml and an executable (what ``launchkit build`` installs)."""
    prefix = tmp_path_factory.mktemp("install")
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "my_interfaces").touch()
    share = prefix / "share" / "my_interfaces"
    for kind, name, text in (
        (
            "msg",
            "Sample.msg",
            "# A sample for the CLI tests\n\nint32 count  # how many\n"
            'geometry_msgs/Vector3 offset\nstring<=8 tag "abc"\nint32 LIMIT=10 # the most\n',
        ),
        ("srv", "Ask.srv", "# the question\nstring question\n---\nbool yes\n"),
        ("action", "Count.action", "int32 target\n---\nint32 reached\n---\nint32 current\n"),
    ):
        (share / kind).mkdir(parents=True)
        (share / kind / name).write_text(text)
    (share / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3">\n  <!-- a comment -->\n'
        "  <name>my_interfaces</name>\n  <version>0.1.0</version>\n</package>\n"
    )
    tool = prefix / "lib" / "my_interfaces" / "tool"
    tool.parent.mkdir(parents=True)
    tool.write_text("#!/bin/sh\necho tool\n")
    tool.chmod(0o755)
    return prefix


def test_interface_show_prints_the_file_as_ros2_does(workspace: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(workspace)}
    shown = launchkit("interface", "show", "my_interfaces/msg/Sample", env=env)
    assert shown.stdout == (
        "# A sample for the CLI tests\n\nint32 count  # how many\n"
        "geometry_msgs/Vector3 offset\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n"
        'string<=8 tag "abc"\nint32 LIMIT=10 # the most\n'
    )
    # without comments: ros2 Jazzy cuts a trailing comment but leaves its '#'
    bare = launchkit("interface", "show", "my_interfaces/msg/Sample", "--no-comments", env=env)
    assert bare.stdout == (
        "int32 count  #\ngeometry_msgs/Vector3 offset\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n"
        'string<=8 tag "abc"\nint32 LIMIT=10 #\n'
    )
    service = launchkit("interface", "show", "my_interfaces/srv/Ask", env=env)
    assert service.stdout == "# the question\nstring question\n---\nbool yes\n"
    action = launchkit("interface", "show", "my_interfaces/action/Count", env=env)
    assert action.stdout == "int32 target\n---\nint32 reached\n---\nint32 current\n"
    piped = launchkit("interface", "show", "-", env=env, stdin="my_interfaces/srv/Ask\n")
    assert piped.stdout == service.stdout


def test_interface_show_of_an_installed_ros_type() -> None:
    prefix = Path(sys.prefix)
    if not (prefix / "share" / "geometry_msgs" / "msg" / "Twist.msg").is_file():
        pytest.skip("the ros-jazzy wheels (their interface files) are not installed here")
    env = {"AMENT_PREFIX_PATH": str(prefix)}
    assert launchkit("interface", "show", "geometry_msgs/msg/Twist", env=env).stdout == (
        "# This expresses velocity in free space broken into its linear and angular parts.\n"
        "\n"
        "Vector3  linear\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n"
        "Vector3  angular\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n"
    )
    nested = launchkit(
        "interface", "show", "geometry_msgs/msg/Twist", "--all-comments", env=env
    ).stdout
    assert "Vector3  linear\n\t# This represents a vector in free space.\n\n" in nested


def test_interface_list_package_packages_and_proto(workspace: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(workspace)}
    listed = launchkit("interface", "list", env=env).stdout
    assert listed.startswith("Messages:\n    ")
    assert "    my_interfaces/msg/Sample\n" in listed and "    std_msgs/msg/String\n" in listed
    assert "\nServices:\n" in listed and "    my_interfaces/srv/Ask\n" in listed
    actions = listed.split("\nActions:\n")[1]  # the last section
    assert "    my_interfaces/action/Count\n" in actions
    only = launchkit("interface", "list", "-s", env=env).stdout
    assert only.startswith("Services:\n") and "Messages:" not in only
    assert launchkit("interface", "package", "my_interfaces", env=env).stdout == (
        "my_interfaces/action/Count\nmy_interfaces/msg/Sample\nmy_interfaces/srv/Ask\n"
    )
    assert launchkit("interface", "package", "-m", "std_srvs").stdout == ""
    assert "std_srvs/srv/SetBool\n" in launchkit("interface", "package", "std_srvs").stdout
    unknown = launchkit("interface", "package", "nope_msgs")
    assert unknown.returncode == 2 and "Unknown package 'nope_msgs'" in unknown.stderr
    packages = launchkit("interface", "packages", env=env).stdout.splitlines()
    assert "my_interfaces" in packages and "geometry_msgs" in packages
    assert "my_interfaces" in launchkit("interface", "packages", "-a", env=env).stdout.split()
    assert launchkit("interface", "proto", "geometry_msgs/msg/Twist").stdout == (
        '"linear:\n  x: 0.0\n  y: 0.0\n  z: 0.0\nangular:\n  x: 0.0\n  y: 0.0\n  z: 0.0\n"\n'
    )
    no_quotes = launchkit("interface", "proto", "std_srvs/srv/SetBool", "--no-quotes")
    assert no_quotes.stdout == "data: false\n\n"


def test_pkg_verbs(workspace: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(workspace)}
    listed = launchkit("pkg", "list", env=env).stdout.splitlines()
    assert "my_interfaces" in listed and "robot_wheel" in listed and listed == sorted(listed)
    assert launchkit("pkg", "prefix", "my_interfaces", env=env).stdout == f"{workspace}\n"
    share = launchkit("pkg", "prefix", "--share", "my_interfaces", env=env).stdout
    assert share == f"{workspace / 'share' / 'my_interfaces'}\n"
    assert (
        launchkit("pkg", "executables", "my_interfaces", env=env).stdout == "my_interfaces tool\n"
    )
    every = launchkit("pkg", "executables", env=env).stdout.splitlines()
    assert "my_interfaces tool" in every and "robot_state_publisher robot_state_publisher" in every
    assert launchkit("pkg", "xml", "my_interfaces", env=env).stdout == (
        # ElementTree's serialization (the comment dropped), as ros2 pkg xml prints it
        '<package format="3">\n  \n  <name>my_interfaces</name>\n'
        "  <version>0.1.0</version>\n</package>\n"
    )
    assert launchkit("pkg", "xml", "my_interfaces", "-t", "version", env=env).stdout == "0.1.0\n"
    missing = launchkit("pkg", "xml", "my_interfaces", "-t", "nothing", env=env)
    assert missing.returncode == 1 and missing.stderr == "XML tag not found\n"


def test_doctor_counts_checks_as_ros2_doctor_does() -> None:
    # nothing answers at the router, and a DDS middleware is set
    endpoint = router_endpoint(free_loopback_port())
    env = {"LAUNCHKIT_ROUTER": endpoint, "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp"}
    passed = launchkit("doctor", env=env)
    assert passed.stdout == "\nAll 5 checks passed\n\n"
    assert f"router: WARNING: no ROS router answers at {endpoint}" in passed.stderr
    strict = launchkit("doctor", "--include-warnings", env=env)
    assert strict.stdout == "\n2/5 check(s) failed\n\nFailed modules: router middleware\n"
    broken = launchkit("doctor", env={**env, "ROS_DOMAIN_ID": "999"})
    assert broken.stdout == "\n1/5 check(s) failed\n\nFailed modules: domain\n"
    assert "domain: ERROR: invalid ROS_DOMAIN_ID '999'" in broken.stderr
    report = launchkit("wtf", "--report", "--exclude-packages", env=env).stdout
    assert report.startswith("\n   PLATFORM INFORMATION\nsystem           : ")
    assert "\n   MIDDLEWARE\n" in report and "\n   PACKAGES\n" not in report
    # each report's items padded to its longest name + 4 (RMW_IMPLEMENTATION here)
    assert f"\nrouter                : {endpoint} (nothing answers)\n" in report
    assert report.endswith("\n   TOPIC LIST\ntopic   : none\n")


def test_doctor_lists_the_topics_of_a_running_graph(graph: list[Child]) -> None:
    report = launchkit("doctor", "--report").stdout
    # every node publishes /rosout, as in ROS 2: knobs and action_graph's own node
    assert (
        "topic               : /rosout\npublisher count     : 2\nsubscriber count    : 0\n"
    ) in report
    assert "answers)" in report and os.environ["LAUNCHKIT_ROUTER"] in report
