"""``launchkit topic|node|service|param|interface`` against running node processes."""

from __future__ import annotations

import subprocess
import sys

import pytest
from ros_helpers import NODES_DIR, Child


def launchkit(*args: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit ARGS`` to completion."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


@pytest.fixture
def talker(router_endpoint: str, children: list[Child]) -> Child:
    """A running talker node."""
    child = Child([str(NODES_DIR / "talker.py")])
    children.append(child)
    child.expect("talker ready", timeout=15)
    return child


def test_topic_commands(talker: Child, children: list[Child]) -> None:
    listed = launchkit("topic", "list", "-t")
    assert listed.returncode == 0 and "/chatter [std_msgs/msg/String]" in listed.stdout
    echo = launchkit("topic", "echo", "/chatter", "--once")
    assert echo.returncode == 0, echo.stderr
    assert echo.stdout.startswith("data: hello ") and echo.stdout.endswith("---\n")
    assert echo.stdout.count("---\n") == 1  # --once: the first message, then exit
    info = launchkit("topic", "info", "/chatter")
    assert "Type: std_msgs/msg/String" in info.stdout and "Publisher count: 1" in info.stdout

    listener = Child([str(NODES_DIR / "listener.py")])
    children.append(listener)
    listener.expect("listener ready", timeout=15)
    pub = launchkit(
        "topic", "pub", "/chatter", "std_msgs/msg/String", "{data: from the cli}", "--once"
    )
    assert pub.returncode == 0, pub.stderr
    assert "publishing #1: std_msgs.msg.String(data='from the cli')\n\n" in pub.stdout
    listener.expect("heard: from the cli", timeout=10)


def test_node_param_and_service_commands(talker: Child) -> None:
    nodes = launchkit("node", "list")
    assert nodes.stdout.split() == ["/talker"]
    info = launchkit("node", "info", "/talker")
    assert "  Publishers:\n    /chatter: std_msgs/msg/String" in info.stdout
    # one node named: its parameters without the node's header line, as ros2 param list
    assert launchkit("param", "list", "/talker").stdout == "  use_sim_time\n"
    assert (
        launchkit("param", "get", "/talker", "use_sim_time").stdout == "Boolean value is: False\n"
    )
    assert launchkit("param", "set", "/talker", "use_sim_time", "true").stdout == (
        "Set parameter successful\n"
    )
    assert launchkit("param", "get", "talker", "use_sim_time").stdout == "Boolean value is: True\n"
    wrong = launchkit("param", "set", "/talker", "use_sim_time", "5")
    assert wrong.returncode == 1 and wrong.stderr.startswith("Setting parameter failed: ")
    call = launchkit(
        "service",
        "call",
        "/talker/get_parameters",
        "rcl_interfaces/srv/GetParameters",
        "{names: [use_sim_time]}",
    )
    assert call.returncode == 0, call.stderr
    assert "response:\nrcl_interfaces.srv.GetParameters_Response(values=[" in call.stdout
    assert "bool_value=True" in call.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["topic", "pub", "/x", "std_msgs/msg/Strin", "{data: a}"], "unknown message type"),
        (["topic", "pub", "/x", "std_msgs/msg/String", "{dat: a}"], "has no field 'dat'"),
        (
            ["topic", "pub", "/x", "geometry_msgs/msg/Twist", "{linear: {x: fast}}"],
            "expected a number",
        ),
        (["topic", "pub", "/x", "std_msgs/msg/String", "{data: [1"], "not valid YAML"),
        (["topic", "echo", "/nothing", "--timeout", "0.3"], "could not determine the type"),
        (["node", "info", "/nobody"], "unknown node /nobody"),
        (["param", "get", "/nobody", "x"], "unknown node /nobody"),
        (["topic", "list", "--router", "nonsense"], "invalid router endpoint"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(
    router_endpoint: str, args: list[str], message: str
) -> None:
    result = launchkit(*args)
    assert result.returncode == 2, result.stderr
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert result.stderr.startswith("error: ")


def test_interface_show() -> None:
    # no interface files installed: the definition rebuilt from the built-in type store
    twist = launchkit("interface", "show", "geometry_msgs/msg/Twist")
    assert twist.stdout.startswith("Vector3 linear\n\tfloat64 x\n")
    srv = launchkit("interface", "show", "gazebo_msgs/srv/DeleteEntity")
    assert srv.stdout == "string name\n---\nbool success\nstring status_message\n"
    # an empty request is empty, as ros2 interface show prints it (no rosidl placeholder)
    trigger = launchkit("interface", "show", "std_srvs/srv/Trigger")
    assert trigger.stdout == "---\nbool success\nstring message\n"
    assert launchkit("interface", "show", "std_msgs/msg/Empty").stdout == ""
    bad = launchkit("interface", "show", "nope_msgs/msg/X")
    assert bad.returncode == 2 and "unknown interface type 'nope_msgs/msg/X'" in bad.stderr


def test_echo_latched_topic_hz_and_lists(talker: Child, children: list[Child]) -> None:
    latched = Child([str(NODES_DIR / "latched_listener.py")])
    children.append(latched)
    latched.expect("latched_listener ready", timeout=15)
    echo = launchkit("topic", "echo", "/status", "--once")  # joins after the only publish
    assert echo.returncode == 0, echo.stderr
    assert echo.stdout == "data: up\n---\n"
    assert launchkit("topic", "type", "/chatter").stdout == "std_msgs/msg/String\n"
    services = launchkit("service", "list", "-t").stdout.splitlines()
    assert "/talker/list_parameters [rcl_interfaces/srv/ListParameters]" in services

    hz = Child(["-m", "launchkit", "topic", "hz", "/chatter"])
    children.append(hz)
    line = hz.expect("average rate:", timeout=15)
    assert float(line.split(":")[1]) > 0  # no timing asserts: the rate itself is load-dependent
    assert hz.stop() == 0


def test_topic_list_shows_topics_of_hidden_nodes_but_not_hidden_topics(
    router_endpoint: str, children: list[Child]
) -> None:
    # `launchkit topic pub` publishes from a hidden node (_launchkit_cli_PID)
    for topic in ("/from_cli", "/_hidden/data"):
        pub = Child(["-m", "launchkit", "topic", "pub", topic, "std_msgs/msg/String", "{}"])
        children.append(pub)
        pub.expect("publishing #1", timeout=30)
    listed = launchkit("topic", "list").stdout.split()
    assert "/from_cli" in listed and "/_hidden/data" not in listed
    assert "/_hidden/data" in launchkit("topic", "list", "-a").stdout.split()


def test_listing_asks_the_router_once_and_gets_the_whole_graph(
    talker: Child, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # each command opens a fresh session and asks once, with no settle loop; the router answers
    # a client's query from everything it knows, so the first answer is the whole graph (a
    # peer's first query used to come back empty about one time in three)
    from launchkit.ros import graph
    from launchkit.ros_cli.main import main

    queries: list[str] = []
    real = graph.snapshot

    def counted(*args: object, **kwargs: object) -> list[object]:
        queries.append("query")
        return list(real(*args, **kwargs))  # type: ignore[arg-type]

    monkeypatch.setattr(graph, "snapshot", counted)
    for _ in range(10):
        assert main("topic", ["list"]) == 0
        assert main("node", ["list"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out.count("/chatter") == 10 and out.count("/talker") == 10
    assert len(queries) == 20


def test_listing_loads_neither_the_message_types_nor_numpy(talker: Child) -> None:
    probe = (
        "import sys\n"
        "from launchkit.cli import main\n"
        "main(sys.argv[1:])\n"
        "heavy = ('numpy', 'rosbags', 'yaml', 'lxml', 'launchkit.ros.node', 'launchkit.ros.msgs')\n"
        "print('LOADED', sorted(m for m in heavy if m in sys.modules))\n"
    )
    for argv in (["topic", "list"], ["node", "info", "/talker"], ["service", "list"]):
        result = subprocess.run(
            [sys.executable, "-c", probe, *argv], capture_output=True, text=True, timeout=60
        )
        assert result.returncode == 0, result.stderr
        assert result.stdout.splitlines()[-1] == "LOADED []", (argv, result.stdout)
