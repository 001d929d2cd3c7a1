"""``launchkit build``: argument parsing (colcon build's option names); the work is in
:mod:`launchkit.workspace.builder`."""

from __future__ import annotations

import argparse
from pathlib import Path

from launchkit._argparse import CommandParser
from launchkit.workspace.builder import BuildOptions, build

DESCRIPTION = """\
Build the ROS 2 workspace in the working folder, as `colcon build` does, for what pip can
build: the packages under src/ (each folder with a package.xml) in dependency order, each into
install/PKG with the ament layout. ament_python packages are built by pip (console scripts in
install/PKG/lib/PKG when setup.cfg says so, data_files under share/); ament_cmake packages
that need no compiler (interfaces by rosidl_generate_interfaces, install(FILES|PROGRAMS|
DIRECTORY)) have their files installed; C++ packages need a ROS install and are skipped.
Then `. install/setup.sh` puts the workspace on AMENT_PREFIX_PATH, PYTHONPATH and PATH."""

EPILOG = """\
exit status: 0 when no package failed (skipped packages are listed), 1 when one failed,
2 for a mistake found before building (no src/, a malformed package.xml, a dependency cycle,
an unknown package name)."""


def build_parser() -> argparse.ArgumentParser:
    """The parser of ``launchkit build``."""
    parser = CommandParser(
        prog="launchkit build",
        description=DESCRIPTION,
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--base-paths",
        nargs="+",
        type=Path,
        metavar="PATH",
        help="where packages are (default src)",
    )
    select = parser.add_argument_group("which packages")
    select.add_argument("--packages-select", nargs="+", metavar="PKG", help="only these")
    select.add_argument(
        "--packages-up-to", nargs="+", metavar="PKG", help="these and what they depend on"
    )
    select.add_argument("--packages-skip", nargs="+", metavar="PKG", help="not these")
    parser.add_argument(
        "--symlink-install",
        action="store_true",
        help="link Python code and data files to the source: edits show without a rebuild",
    )
    for name, job in (
        ("build", "pip's working copies"),
        ("install", "the packages"),
        ("log", "logs"),
    ):
        parser.add_argument(
            f"--{name}-base",
            type=Path,
            default=Path(name),
            metavar="PATH",
            help=f"where {job} go (default {name})",
        )
    parser.add_argument(
        "--parallel-workers",
        type=_positive,
        default=BuildOptions.workers,
        metavar="N",
        help="packages built at once (default %(default)s)",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    return parser


def _positive(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value} is not at least 1")
    return value


def main(argv: list[str]) -> int:
    """Run ``launchkit build ARGV``; the exit status."""
    args = build_parser().parse_args(argv)
    options = BuildOptions(
        base_paths=tuple(args.base_paths) if args.base_paths else None,
        build_base=args.build_base,
        install_base=args.install_base,
        log_base=args.log_base,
        select=args.packages_select,
        up_to=args.packages_up_to,
        skip=args.packages_skip,
        symlink_install=args.symlink_install,
        workers=args.parallel_workers,
    )
    return build(options)
