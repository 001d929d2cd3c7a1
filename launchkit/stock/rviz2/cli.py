"""rviz2's command line: ``[-d CONFIG.rviz] [-f FRAME] [--port N] [--address A]
[--allow-origin URL ...] [--ros-args ... [--]]``.

The options give the defaults of the node's parameters ``port``, ``address`` and
``allowed_origins``; a parameter set with ``-p`` or ``<param>`` wins.

Real rviz2's other options (Jazzy: ``-s/--splash-screen``, ``-l/--ogre-log``,
``-t/--display-title-format``, ``--fullscreen``), those of ROS 1's rviz that launch files still
pass (``--opengl``, ``--disable-anti-aliasing``, ``--no-stereo``, ...) and Qt's own
(``-platform``, ``-style``, ...) mean nothing to a browser viewer: they are accepted and
ignored (:attr:`Namespace.ignored`, which the node reports in one line), so a launch file
written for rviz2 runs, and a respawning rviz2 does not exit at once on each start. An option
real rviz2 does not know either is an error, as there.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import NoReturn

# PORT_ENV sets the default port, e.g. for launch files whose rviz2 line cannot be changed.
from launchkit.envvars import VIEWER_PORT as PORT_ENV
from launchkit.errors import UserError

DEFAULT_PORT = 8765
DEFAULT_ADDRESS = "127.0.0.1"


#: Options of rviz2 (Jazzy), of ROS 1's rviz and of Qt that mean nothing to the browser
#: viewer: whether each takes a value.
IGNORED_OPTIONS: dict[str, bool] = {
    # rviz2
    "-s": True,
    "--splash-screen": True,
    "-l": False,
    "--ogre-log": False,
    "-t": True,
    "--display-title-format": True,
    "--fullscreen": False,
    # ROS 1's rviz
    "--opengl": True,
    "--disable-anti-aliasing": False,
    "--no-stereo": False,
    "--stereo": False,
    "--help-file": True,
    "--in-mc-wrapper": False,
    "-v": False,
    "--verbose": False,
    "--log-level-debug": False,
    # Qt's (QApplication's)
    "-platform": True,
    "-platformpluginpath": True,
    "-platformtheme": True,
    "-plugin": True,
    "-style": True,
    "-stylesheet": True,
    "-display": True,
    "-geometry": True,
    "-qwindowgeometry": True,
    "-qwindowtitle": True,
    "-qwindowicon": True,
    "-session": True,
    "-reverse": False,
    "-widgetcount": False,
    "-nograb": False,
    "-dograb": False,
    "-sync": False,
}


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        usage = " ".join(self.format_usage().split())  # one line: argparse wraps it
        raise UserError(f"rviz2: {message}", expected=usage)


def _split_ignored(argv: list[str]) -> tuple[list[str], list[str]]:
    """``argv`` without the options of :data:`IGNORED_OPTIONS` (and their values), and those."""
    kept: list[str] = []
    ignored: list[str] = []
    index = 0
    while index < len(argv):
        word = argv[index]
        name, equals, _ = word.partition("=")
        takes_value = IGNORED_OPTIONS.get(name)
        index += 1
        if takes_value is None:
            kept.append(word)
            continue
        ignored.append(word)
        if takes_value and not equals and index < len(argv):
            ignored.append(argv[index])
            index += 1
    return kept, ignored


def parse_args(argv: list[str]) -> argparse.Namespace:
    """rviz2's own options; ``--ros-args ... [--]`` is left to the ROS layer, and the options
    that mean nothing here are in ``ignored``."""
    own = list(argv)
    if "--ros-args" in own:
        start = own.index("--ros-args")
        end = own.index("--", start) + 1 if "--" in own[start:] else len(own)
        del own[start:end]
    own, ignored = _split_ignored(own)
    parser = _Parser(prog="rviz2", description=__doc__, allow_abbrev=False)
    parser.add_argument("-d", "--display-config", type=Path, help="an .rviz config (YAML)")
    parser.add_argument("-f", "--fixed-frame", help="override the config's fixed frame")
    parser.add_argument(
        "--port",
        type=int,
        default=default_port(),
        help=f"viewer and Foxglove WebSocket port (default ${PORT_ENV} or {DEFAULT_PORT}; "
        "0 picks a free one)",
    )
    parser.add_argument(
        "--address",
        default=DEFAULT_ADDRESS,
        help=f"address to listen on (default {DEFAULT_ADDRESS}: this machine only)",
    )
    parser.add_argument(
        "--allow-origin",
        action="append",
        default=[],
        metavar="URL",
        help="also accept WebSocket connections from pages of this origin (repeatable; * for any)",
    )
    args = parser.parse_args(own)
    args.ignored = ignored
    return args


def default_port() -> int:
    """``$LAUNCHKIT_VIEWER_PORT``, or 8765."""
    value = os.environ.get(PORT_ENV, str(DEFAULT_PORT))
    if not value.isdigit() or not 0 <= int(value) <= 65535:
        raise UserError(f"{PORT_ENV} is {value!r}", expected="a port number, 0 to 65535")
    return int(value)
