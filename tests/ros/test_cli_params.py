"""``launchkit param ...`` and ``launchkit service ...`` against a running node, compared with
what ``ros2 param`` and ``ros2 service`` print (ros2cli's ros2param and ros2service, Jazzy)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml
from cli_helpers import graph_of, launchkit
from ros_helpers import Child

OURS = ["count", "enabled", "flags", "gains", "ids", "label", "names", "nested.depth", "rate"]


@pytest.fixture(scope="module")
def graph() -> Iterator[list[Child]]:
    """/knobs: parameters of every kind and the service /knobs/toggle."""
    with graph_of("knobs") as children:
        yield children


def test_list_describes_each_parameter(graph: list[Child]) -> None:
    lines = launchkit("param", "list", "/knobs").stdout.splitlines()
    # one node named: no header line, each name indented, sorted
    assert all(line.startswith("  ") for line in lines) and lines == sorted(lines)
    assert [line for line in lines if line.strip() in OURS] == [f"  {name}" for name in OURS]
    every = launchkit("param", "list").stdout
    assert "/knobs:\n  count\n  enabled\n" in every
    typed = launchkit("param", "list", "/knobs", "--param-type").stdout.splitlines()
    assert "  count (type: integer)" in typed and "  gains (type: double array)" in typed
    assert "  flags (type: boolean array)" in typed and "  label (type: string)" in typed
    filtered = launchkit("param", "list", "/knobs", "--filter", "n.*").stdout
    assert filtered == "  names\n  nested.depth\n"
    described = launchkit("param", "describe", "/knobs", "count", "label").stdout
    assert described == (
        "Parameter name: count\n  Type: integer\n  Constraints:\n"
        "Parameter name: label\n  Type: string\n  Constraints:\n"
    )


@pytest.mark.parametrize(
    ("name", "printed"),
    [
        ("count", "Integer value is: 5"),
        ("rate", "Double value is: 2.5"),
        ("label", "String value is: hi there"),
        ("enabled", "Boolean value is: True"),
        ("ids", "Integer values are: [1, 2, 3]"),
        ("gains", "Double values are: [0.5, 1.5]"),
        ("names", "String values are: ['a', 'b']"),
        ("flags", "Boolean values are: [True, False]"),
        ("nested.depth", "Integer value is: 3"),
    ],
)
def test_get_prints_the_value_with_its_type(graph: list[Child], name: str, printed: str) -> None:
    assert launchkit("param", "get", "/knobs", name).stdout == printed + "\n"


def test_set_get_dump_load_and_delete(graph: list[Child], tmp_path: Path) -> None:
    assert launchkit("param", "get", "knobs", "count", "--hide-type").stdout == "5\n"
    assert launchkit("param", "set", "/knobs", "count", "7").stdout == "Set parameter successful\n"
    assert launchkit("param", "get", "/knobs", "count").stdout == "Integer value is: 7\n"
    refused = launchkit("param", "set", "/knobs", "count", "1.5")
    assert refused.returncode == 1 and refused.stdout == ""
    assert refused.stderr.startswith("Setting parameter failed: ")
    # ros2's two answers to an undeclared name: none at all (rclpy's nodes), or a value of type
    # NOT_SET (launchkit.ros's nodes before its rclpy face)
    unknown = launchkit("param", "get", "/knobs", "nope")
    assert unknown.stdout == "Parameter not set.\n" or (
        unknown.returncode == 2 and "Parameter not set" in unknown.stderr
    ), (unknown.stdout, unknown.stderr)

    dump = launchkit("param", "dump", "/knobs").stdout
    assert dump.startswith(
        "/knobs:\n  ros__parameters:\n    count: 7\n    enabled: true\n    flags:\n    - true\n"
        "    - false\n    gains:\n    - 0.5\n    - 1.5\n    ids:\n    - 1\n    - 2\n    - 3\n"
        "    label: hi there\n    names:\n    - a\n    - b\n    nested:\n      depth: 3\n"
        "    rate: 2.5\n"
    )
    assert dump.endswith("    use_sim_time: false\n\n")  # yaml.dump's text, then print's newline
    saved = launchkit("param", "dump", "/knobs", "--output-dir", str(tmp_path))
    assert saved.stdout == f"Saving to:  {tmp_path / 'knobs.yaml'}\n"
    assert (tmp_path / "knobs.yaml").read_text() == dump[:-1]

    params = tmp_path / "params.yaml"
    params.write_text(
        "/knobs:\n  ros__parameters:\n    count: 9\n    nested:\n      depth: 4\n"
        "/**:\n  ros__parameters:\n    rate: 4.0\n"
        "/other:\n  ros__parameters:\n    count: 100\n"
    )
    loaded = launchkit("param", "load", "/knobs", str(params))
    assert loaded.stdout == (
        "Set parameter rate successful\n"
        "Set parameter count successful\n"
        "Set parameter nested.depth successful\n"
    )
    values = yaml.safe_load(launchkit("param", "dump", "/knobs").stdout)["/knobs"]
    assert values["ros__parameters"]["count"] == 9
    assert values["ros__parameters"]["nested"] == {"depth": 4}
    assert values["ros__parameters"]["rate"] == 4.0
    only_node = launchkit("param", "load", "/knobs", str(params), "--no-use-wildcard").stdout
    assert "rate" not in only_node and "Set parameter count successful\n" in only_node

    deleted = launchkit("param", "delete", "/knobs", "label")
    assert re.fullmatch(r"Deleted parameter successfully(: .*)?\n", deleted.stdout) or (
        re.fullmatch(r"Deleting parameter failed(: .*)?\n", deleted.stderr)
    ), (deleted.stdout, deleted.stderr)


def test_bad_parameter_files_are_one_line_errors(graph: list[Child], tmp_path: Path) -> None:
    broken = tmp_path / "broken.yaml"
    broken.write_text("/knobs:\n  ros__parameters: [\n")
    result = launchkit("param", "load", "/knobs", str(broken))
    assert result.returncode == 2 and result.stderr.startswith(f"{broken}:")
    elsewhere = tmp_path / "elsewhere.yaml"
    elsewhere.write_text("/other:\n  ros__parameters:\n    a: 1\n")
    result = launchkit("param", "load", "/knobs", str(elsewhere))
    assert result.returncode == 2
    assert "Param file does not contain parameters for /knobs" in result.stderr


def test_service_verbs(graph: list[Child]) -> None:
    assert "/knobs/toggle" in launchkit("service", "list").stdout.splitlines()
    typed = launchkit("service", "list", "-t").stdout.splitlines()
    assert "/knobs/toggle [std_srvs/srv/SetBool]" in typed
    assert launchkit("service", "list", "-c").stdout == f"{len(typed)}\n"
    assert launchkit("service", "type", "/knobs/toggle").stdout == "std_srvs/srv/SetBool\n"
    assert launchkit("service", "find", "std_srvs/srv/SetBool").stdout == "/knobs/toggle\n"
    assert launchkit("service", "find", "-c", "std_srvs/srv/SetBool").stdout == "1\n"
    called = launchkit("service", "call", "/knobs/toggle", "std_srvs/srv/SetBool", "{data: true}")
    # ros2 says it waits when its fresh node has not seen the server yet; it may, on a busy machine
    waited = "waiting for service to become available...\n"
    assert called.stdout.removeprefix(waited) == (
        "requester: making request: std_srvs.srv.SetBool_Request(data=True)\n\n"
        "response:\n"
        "std_srvs.srv.SetBool_Response(success=True, message='toggled to True')\n\n"
    )
    repeated = Child(
        ["-m", "launchkit", "service", "call", "-r", "20", "/knobs/toggle", "std_srvs/srv/SetBool"]
    )
    try:
        for _ in range(3):
            repeated.expect(
                "std_srvs.srv.SetBool_Response(success=True, message='toggled to False')"
            )
    finally:
        assert repeated.stop() == 0
