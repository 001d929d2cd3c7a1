"""rviz2's command line: ``[-d CONFIG.rviz] [-f FRAME] [--port N] [--address A]
[--allow-origin URL ...] [--ros-args ... [--]]``.

The options give the defaults of the node's parameters ``port``, ``address`` and
``allowed_origins``; a parameter set with ``-p`` or ``<param>`` wins.
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


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UserError(f"rviz2: {message}", expected=self.format_usage().strip())


def parse_args(argv: list[str]) -> argparse.Namespace:
    """rviz2's own options; ``--ros-args ... [--]`` is left to the ROS layer."""
    own = list(argv)
    if "--ros-args" in own:
        start = own.index("--ros-args")
        end = own.index("--", start) + 1 if "--" in own[start:] else len(own)
        del own[start:end]
    parser = _Parser(prog="rviz2", description=__doc__)
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
    parser.add_argument(
        "--asset-folder",
        action="append",
        default=[],
        type=Path,
        metavar="DIR",
        help="also serve the mesh and texture files robot descriptions name in DIR (repeatable; "
        "package share folders always are)",
    )
    return parser.parse_args(own)


def default_port() -> int:
    """``$LAUNCHKIT_VIEWER_PORT``, or 8765."""
    value = os.environ.get(PORT_ENV, str(DEFAULT_PORT))
    if not value.isdigit() or not 0 <= int(value) <= 65535:
        raise UserError(f"{PORT_ENV} is {value!r}", expected="a port number, 0 to 65535")
    return int(value)
