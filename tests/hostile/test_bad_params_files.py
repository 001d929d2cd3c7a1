"""Issue #17, point 1: parameter files that gave a traceback in the node (bytes that are not
UTF-8), took 15 s and 1.4 GB (an alias bomb) or hung (a base-60 number of 20 000 digits) are a
located error: from the node itself (exit status 2) and, for ``<param from>``, from ``check``
and ``run`` before anything starts. One reader does it all: launchkit/safe_yaml.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit import safe_yaml
from tests.hostile.helpers import CORPUS, assert_located_error, launchkit

#: file -> (where, what), regular expressions
CASES = {
    "params_latin1.yaml": (r"params_latin1\.yaml:4:\d+", "not UTF-8 text"),
    "params_alias_bomb.yaml": (
        r"params_alias_bomb\.yaml:\d+:\d+",
        f"aliases expand to more than {safe_yaml.MAX_ALIAS_NODES} nodes",
    ),
    "params_base60.yaml": (
        r"params_base60\.yaml:3:\d+",
        f"an unquoted int of 40001 characters.*at most {safe_yaml.MAX_NUMBER_LENGTH}",
    ),
    "params_long_int.yaml": (r"params_long_int\.yaml:3:\d+", "an unquoted int of 5000"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_stock_node_reports_a_bad_params_file_in_one_line(name: str) -> None:
    where, message = CASES[name]
    result = launchkit(
        "exec",
        "robot_state_publisher",
        "robot_state_publisher",
        "--ros-args",
        "--params-file",
        CORPUS / name,
    )
    assert_located_error(result, where, message)
    assert result.stderr.startswith("robot_state_publisher: ")


@pytest.mark.parametrize("command", ["check", "run"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_the_launcher_refuses_a_bad_param_from_file(
    tmp_path: Path, name: str, command: str
) -> None:
    where, message = CASES[name]
    path = tmp_path / "node.launch.xml"
    path.write_text(
        "<launch>\n"
        '  <node pkg="robot_state_publisher" exec="robot_state_publisher">\n'
        f'    <param from="{CORPUS / name}"/>\n'
        "  </node>\n"
        "</launch>\n"
    )
    assert_located_error(launchkit(command, path), where, message)


def test_merge_keys_and_anchors_of_an_ordinary_params_file_still_load(tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_text(
        "defaults: &defaults {rate: 10, frame: base}\n"
        "/**:\n"
        "  ros__parameters:\n"
        "    <<: *defaults\n"
        "    frame: odom\n"
        "    limits: {max: [1, 2.5], name: 'x'}\n"
    )
    from launchkit.ros.params import load_params_file

    assert load_params_file(path, "/any/node") == {
        "rate": 10,
        "frame": "odom",
        "limits.max": [1, 2.5],
        "limits.name": "x",
    }


def test_a_params_file_that_never_ends_is_refused_at_once() -> None:
    # /dev/zero is no regular file: reading it would never end (and fill memory)
    result = launchkit(
        "exec", "robot_state_publisher", "robot_state_publisher", "--ros-args",
        "--params-file", "/dev/zero",
    )  # fmt: skip
    assert_located_error(result, "/dev/zero", "not a regular file")
