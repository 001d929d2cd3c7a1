"""``launchkit pkg list|prefix|share|executables|xml``: the package index as ``ros2 pkg`` shows
it (packages registered by Python distributions, and those of ``AMENT_PREFIX_PATH``)."""

from __future__ import annotations

import argparse
import os
import sys
import xml.etree.ElementTree as ElementTree
from typing import Any

from launchkit.errors import PackageNotFoundError
from launchkit.packages import PackageIndex
from launchkit.ros_cli.common import CliUsageError


def add_parser(commands: Any) -> None:
    """Register the ``pkg`` verbs."""
    pkg = commands.add_parser("pkg", help="packages: list, prefix, executables, xml")
    sub = pkg.add_subparsers(dest="verb", metavar="VERB", required=True)
    sub.add_parser("list", help="Output a list of available packages").set_defaults(run=_list)
    p = sub.add_parser("prefix", help="Output the prefix path of a package")
    p.add_argument("package_name")
    p.add_argument("--share", action="store_true", help="the share directory instead")
    p.set_defaults(run=_prefix)
    p = sub.add_parser("share", help="Output the share directory of a package")
    p.add_argument("package_name")
    p.set_defaults(run=_share)
    p = sub.add_parser("executables", help="Output a list of package specific executables")
    p.add_argument("package_name", nargs="?")
    p.add_argument("--full-path", action="store_true", help="the command that runs each")
    p.set_defaults(run=_executables)
    p = sub.add_parser("xml", help="Output the package manifest, or one of its tags")
    p.add_argument("package_name")
    p.add_argument("-t", "--tag", help="the tag to print (e.g. version)")
    p.set_defaults(run=_xml)


def _list(args: argparse.Namespace) -> int:
    # one name a line, as `ros2 pkg list`; a name served by launchkit's stand-in says so, so a
    # user sees whether the real package (installed, on AMENT_PREFIX_PATH) or the stand-in runs
    index = PackageIndex()
    for name in index.names():
        print(f"{name}  (launchkit stand-in)" if index.find(name).source == "stand-in" else name)
    return 0


def _prefix(args: argparse.Namespace) -> int:
    index = PackageIndex()
    print(index.share_dir(args.package_name) if args.share else index.prefix(args.package_name))
    return 0


def _share(args: argparse.Namespace) -> int:
    print(PackageIndex().share_dir(args.package_name))
    return 0


def _executables(args: argparse.Namespace) -> int:
    index = PackageIndex()
    names = [args.package_name] if args.package_name else index.names()
    for package in names:
        for executable in index.executables(package):
            if args.full_path:
                print(" ".join(index.executable(package, executable)))
            else:
                print(package, executable)
    return 0


def _xml(args: argparse.Namespace) -> int:
    manifest = PackageIndex().share_dir(args.package_name) / "package.xml"
    if not os.path.isfile(manifest):
        raise PackageNotFoundError(
            f"Package XML manifest not found: {manifest}",
            expected=f"a package.xml in the share folder of '{args.package_name}'",
        )
    try:
        tree = ElementTree.parse(manifest)
    except ElementTree.ParseError as error:
        line, column = error.position
        raise CliUsageError(f"{manifest}:{line}:{column + 1}: {error.msg}") from None
    if args.tag is None:
        # ElementTree's serialization, as ros2 pkg xml prints it (comments dropped)
        ElementTree.dump(tree)
        return 0
    elements = tree.getroot().findall(args.tag)
    if not elements:
        print("XML tag not found", file=sys.stderr)
        return 1
    for element in elements:
        print(element.text)
    return 0
