"""Parsing ``--ros-args`` sections of a node's command line, as rcl does."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from launchkit.errors import UserError
from launchkit.ros.names import RemapRule

LOG_LEVELS = ("debug", "info", "warn", "error", "fatal", "unset")


class RosArgumentError(UserError):
    """A malformed ``--ros-args`` section."""


@dataclass
class RosArguments:
    """What the ``--ros-args`` sections of a command line say."""

    remaps: list[RemapRule] = field(default_factory=list)
    # (node name or None, parameter name, YAML text), in command-line order
    params: list[tuple[str | None, str, str]] = field(default_factory=list)
    params_files: list[Path] = field(default_factory=list)
    log_levels: dict[str, str] = field(default_factory=dict)  # "" is the default level
    enclave: str = "/"
    # which of params / params files came first: ("p", index) or ("f", index)
    param_order: list[tuple[str, int]] = field(default_factory=list)
    rosout_logs: bool = True  # --disable-rosout-logs: nodes publish nothing on /rosout
    stdout_logs: bool = True  # --disable-stdout-logs: loggers print nothing


_FLAGS_WITHOUT_VALUE = {
    "--enable-rosout-logs",
    "--disable-rosout-logs",
    "--enable-stdout-logs",
    "--disable-stdout-logs",
    "--enable-external-lib-logs",
    "--disable-external-lib-logs",
}


def split_ros_args(argv: list[str]) -> tuple[list[str], list[str]]:
    """Split ``argv`` into (ordinary arguments, items inside ``--ros-args`` sections)."""
    plain: list[str] = []
    ros: list[str] = []
    inside = False
    for item in argv:
        if item == "--ros-args":
            inside = True
        elif inside and item == "--":
            inside = False
        elif inside:
            ros.append(item)
        else:
            plain.append(item)
    return plain, ros


def remove_ros_args(argv: list[str]) -> list[str]:
    """``argv`` without its ``--ros-args`` sections (rclpy's ``remove_ros_args``)."""
    return split_ros_args(argv)[0]


def parse_ros_args(argv: list[str]) -> RosArguments:
    """Parse every ``--ros-args`` section in ``argv``; errors name the offending item."""
    _, items = split_ros_args(argv)
    result = RosArguments()
    i = 0
    while i < len(items):
        flag = items[i]
        if flag in _FLAGS_WITHOUT_VALUE:
            if flag.endswith("-rosout-logs"):
                result.rosout_logs = flag.startswith("--enable")
            elif flag.endswith("-stdout-logs"):
                result.stdout_logs = flag.startswith("--enable")
            i += 1
            continue
        if i + 1 >= len(items):
            raise RosArgumentError(
                f"--ros-args: {flag!r} needs a value"
                if flag.startswith("-")
                else f"--ros-args: unexpected {flag!r}",
                expected=_EXPECTED,
            )
        value = items[i + 1]
        if flag in ("-r", "--remap"):
            result.remaps.append(RemapRule.parse(value))
        elif flag in ("-p", "--param"):
            result.params.append(_parse_param(value))
            result.param_order.append(("p", len(result.params) - 1))
        elif flag == "--params-file":
            result.params_files.append(Path(value))
            result.param_order.append(("f", len(result.params_files) - 1))
        elif flag == "--log-level":
            logger, sep, level = value.rpartition(":=")
            level = level.lower()
            if level not in LOG_LEVELS:
                raise RosArgumentError(
                    f"--log-level: unknown level {value!r}",
                    expected="one of " + ", ".join(LOG_LEVELS),
                )
            result.log_levels[logger if sep else ""] = level
        elif flag in ("-e", "--enclave"):
            result.enclave = value
        elif flag == "--log-config-file":
            pass
        else:
            raise RosArgumentError(f"unknown ROS argument {flag!r}", expected=_EXPECTED)
        i += 2
    return result


_EXPECTED = "-r from:=to, -p name:=value, --params-file FILE, --log-level LEVEL"


def _parse_param(text: str) -> tuple[str | None, str, str]:
    name, sep, value = text.partition(":=")
    if not sep or not name:
        raise RosArgumentError(f"invalid parameter argument {text!r}", expected="-p name:=value")
    node: str | None = None
    if ":" in name:
        node, _, name = name.partition(":")
    return node, name, value
