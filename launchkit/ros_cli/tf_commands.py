"""``launchkit tf view-frames``: tf2_tools' ``view_frames``, the TF tree as a picture.

It listens to ``/tf`` and ``/tf_static`` for ``--wait-time`` seconds (5), then writes the tree
as ``frames_YYYY-MM-DD_HH.MM.SS.gv`` (Graphviz dot: each frame's parent, broadcaster, average
rate and buffer span) and, as view_frames does, renders it to ``.pdf`` with Graphviz's ``dot``.
Where Graphviz is not installed it writes an ``.svg`` of the same tree instead (drawn by
:mod:`.frames_picture`) and says so: a PDF writer is no reason for a heavy dependency.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import time
from pathlib import Path
from typing import Any

from launchkit.errors import RuntimeLaunchError
from launchkit.ros_cli.common import CliUsageError, add_router_option, cli_node
from launchkit.ros_cli.frames_picture import to_dot, to_svg


def add_parser(commands: Any) -> None:
    """Register the ``tf`` subcommands."""
    tf = commands.add_parser("tf", help="transforms: view-frames")
    sub = tf.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = sub.add_parser(
        "view-frames",
        help="listen to TF, then write the tree as frames_<time>.gv and .pdf (or .svg)",
    )
    p.add_argument(
        "-t",
        "--wait-time",
        type=float,
        default=5.0,
        help="seconds to listen to /tf before drawing the tree (5)",
    )
    p.add_argument("-o", "--output", help="file name without suffix (frames_<time>)")
    add_router_option(p)
    p.set_defaults(run=_view_frames)


def _view_frames(args: argparse.Namespace) -> int:
    import yaml

    import launchkit.ros as ros
    from launchkit.ros.logging import get_logger
    from launchkit.ros.tf2.buffer import Buffer
    from launchkit.ros.tf2.transform_listener import TransformListener

    if not args.wait_time >= 0:
        raise CliUsageError(f"--wait-time {args.wait_time}", expected="seconds, 0 or more")
    logger = get_logger("view_frames")
    base = args.output or f"frames_{time.strftime('%Y-%m-%d_%H.%M.%S')}"
    with cli_node(args) as node:
        buffer = Buffer(node=None)
        listener = TransformListener(buffer, node)
        logger.info(f"Listening to tf data for {args.wait_time} seconds...")
        deadline = time.monotonic() + args.wait_time
        while time.monotonic() < deadline:
            ros.spin_once(node, timeout_sec=min(0.1, max(deadline - time.monotonic(), 0.0)))
        logger.info("Generating graph...")
        frames = yaml.safe_load(buffer.all_frames_as_yaml()) or {}
        seconds, nanoseconds = node.get_clock().now().seconds_nanoseconds()
        listener.unregister()
    recorded_at = seconds + nanoseconds / 1e9
    gv, pdf, svg = (Path(f"{base}.{suffix}") for suffix in ("gv", "pdf", "svg"))
    dot = shutil.which("dot")
    logger.info(f"Exporting graph in {pdf if dot else svg} file...")
    gv.write_text(to_dot(frames, recorded_at))
    if dot is None:
        svg.write_text(to_svg(frames, recorded_at))
        logger.warning(
            f"Graphviz's dot is not installed: wrote {svg} (and {gv}) instead of a PDF; "
            f"install graphviz (apt install graphviz) for {pdf}"
        )
        return 0
    done = subprocess.run([dot, "-Tpdf", str(gv), "-o", str(pdf)], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeLaunchError(f"dot could not render {gv}: {done.stderr.strip()}")
    return 0
