"""rviz2's command line: ``[-d CONFIG.rviz] [-f FRAME] [--port N] [--ros-args ... [--]]``."""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import NoReturn

# PORT_ENV sets the default port, e.g. for launch files whose rviz2 line cannot be changed.
from launchkit.envvars import FOXGLOVE_PORT as PORT_ENV
from launchkit.errors import UserError


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
        default=_default_port(),
        help=f"WebSocket port (default ${PORT_ENV} or 8765)",
    )
    return parser.parse_args(own)


def _default_port() -> int:
    value = os.environ.get(PORT_ENV, "8765")
    if not value.isdigit() or not 0 <= int(value) <= 65535:
        raise UserError(f"{PORT_ENV} is {value!r}", expected="a port number, 0 to 65535")
    return int(value)
