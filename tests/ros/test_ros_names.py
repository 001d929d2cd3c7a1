"""Name expansion and remapping follow rcl exactly."""

from __future__ import annotations

import pytest

from launchkit.errors import UserError
from launchkit.ros.arguments import parse_ros_args, remove_ros_args
from launchkit.ros.names import RemapRule, expand, remap_name, remap_namespace, remap_node_name


@pytest.mark.parametrize(
    ("name", "ns", "expected"),
    [
        ("chatter", "/", "/chatter"),
        ("chatter", "/robot", "/robot/chatter"),
        ("/abs", "/robot", "/abs"),
        ("~/private", "/robot", "/robot/node/private"),
        ("~/private", "/", "/node/private"),
        ("~", "/robot", "/robot/node"),
        ("{node}/x", "/robot", "/robot/node/x"),
    ],
)
def test_expand(name: str, ns: str, expected: str) -> None:
    assert expand(name, "node", ns) == expected


@pytest.mark.parametrize("bad", ["", "a//b", "a/", "1abc", "a b", "~x"])
def test_invalid_names(bad: str) -> None:
    with pytest.raises(UserError):
        expand(bad, "node", "/")


def test_remapping_rules() -> None:
    rules = [RemapRule.parse(r) for r in ["other:chatter:=/x", "chatter:=news", "__ns:=/r"]]
    ns = remap_namespace(rules, "node", "/")
    assert ns == "/r"
    assert remap_name(rules, "/r/chatter", "node", "node", ns) == "/r/news"
    assert remap_name(rules, "/r/chatter", "other", "other", ns) == "/x"
    assert remap_node_name([RemapRule.parse("__node:=renamed")], "node") == "renamed"
    assert remap_node_name([RemapRule.parse("x:__node:=renamed")], "node") == "node"


def test_ros_args_parsing() -> None:
    argv = [
        "prog",
        "keep",
        "--ros-args",
        "-r",
        "a:=b",
        "-p",
        "x:=1",
        "--params-file",
        "f.yaml",
        "--log-level",
        "debug",
        "--",
        "also",
    ]
    args = parse_ros_args(argv)
    assert remove_ros_args(argv) == ["prog", "keep", "also"]
    assert [(r.src, r.dst) for r in args.remaps] == [("a", "b")]
    assert args.params == [(None, "x", "1")]
    assert [str(p) for p in args.params_files] == ["f.yaml"]
    assert args.log_levels == {"": "debug"}


@pytest.mark.parametrize(
    "bad",
    [
        ["--ros-args", "-r", "nope"],
        ["--ros-args", "--bogus"],
        ["--ros-args", "-p"],
        ["--ros-args", "--log-level", "loud"],
    ],
)
def test_bad_ros_args_are_user_errors(bad: list[str]) -> None:
    with pytest.raises(UserError):
        parse_ros_args(bad)
