"""``launchkit doctor``: what launchkit can check of this machine's ROS setup, printed in the
shape of ``ros2 doctor`` (a count of passed checks; ``--report`` for every report).

Checks: the ROS router answers, ``ROS_DOMAIN_ID`` is valid, the middleware setting fits
(launchkit speaks rmw_zenoh's wire format: another ``RMW_IMPLEMENTATION`` reaches it only through
``launchkit bridge``), which rclpy the processes launchkit starts get, and the package index.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import os
import platform
import sys
from collections.abc import Callable
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from launchkit.errors import LaunchkitError
from launchkit.packages import PackageIndex
from launchkit.ros.endpoints import router_endpoint
from launchkit.ros.keyexpr import domain_id
from launchkit.ros.router_access import router_answers

#: a check's outcome: (errors, warnings), each a list of messages
Outcome = tuple[list[str], list[str]]
Report = tuple[str, list[tuple[str, str]]]


def add_parser(commands: Any) -> None:
    """Register ``doctor`` (and its ``wtf`` alias, as ros2 has it)."""
    for name in ("doctor", "wtf"):
        p = commands.add_parser(name, help="check the ROS setup (router, domain, rclpy, packages)")
        reports = p.add_mutually_exclusive_group()
        reports.add_argument("--report", "-r", action="store_true", help="print every report")
        reports.add_argument(
            "--report-failed", "-rf", action="store_true", help="print the failed checks' reports"
        )
        p.add_argument("--exclude-packages", "-ep", action="store_true", help="no package check")
        p.add_argument(
            "--include-warnings", "-iw", action="store_true", help="count warnings as failures"
        )
        p.set_defaults(run=_doctor)


def _router() -> Outcome:
    endpoint = router_endpoint(None)
    if router_answers(endpoint):
        return [], []
    return [], [
        f"no ROS router answers at {endpoint} (a launch or any launchkit command starts one; "
        "`launchkit router start` starts the shared one)"
    ]


def _domain() -> Outcome:
    try:
        domain_id()
    except LaunchkitError as error:
        return [error.format().removeprefix("error: ")], []
    return [], []


def _middleware() -> Outcome:
    rmw = os.environ.get("RMW_IMPLEMENTATION", "")
    if rmw and rmw != "rmw_zenoh_cpp":
        return [], [
            f"RMW_IMPLEMENTATION={rmw}: launchkit's nodes speak rmw_zenoh's wire format; ROS 2 "
            "nodes on this middleware reach them only through `launchkit bridge`"
        ]
    return [], []


def _rclpy() -> Outcome:
    choice, detail = rclpy_choice()
    if choice == "ros" and importlib.util.find_spec("rclpy") is None:
        return [f"processes get the real rclpy ({detail}), but none can be imported"], []
    return [], []


def rclpy_choice() -> tuple[str, str]:
    """Which rclpy the processes launchkit starts get (``launchkit`` or ``ros``), and why."""
    # the choice is launchkit.ros.face.choose's, where this version has the rclpy face
    choose = getattr(importlib.import_module("launchkit.ros.face"), "choose", None)
    if choose is None:
        return "launchkit", "launchkit.ros; this version has no rclpy face"
    return str(choose(os.environ)), "LAUNCHKIT_RCLPY or a sourced ROS 2 install decides"


def _packages() -> Outcome:
    missing = [
        p
        for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep)
        if p and not os.path.isdir(p)
    ]
    try:
        PackageIndex().names()
    except LaunchkitError as error:
        return [error.format().removeprefix("error: ")], []
    return [], [f"AMENT_PREFIX_PATH names a missing folder: {p}" for p in missing]


CHECKS: dict[str, Callable[[], Outcome]] = {
    "router": _router,
    "domain": _domain,
    "middleware": _middleware,
    "rclpy": _rclpy,
    "packages": _packages,
}


def _version(distribution: str) -> str:
    try:
        return version(distribution)
    except PackageNotFoundError:
        return "not installed"


def reports(exclude_packages: bool) -> list[Report]:
    """Every report: platform, launchkit, middleware, packages (unless excluded), topics."""
    endpoint = router_endpoint(None)
    up = router_answers(endpoint)
    out: list[Report] = [
        (
            "PLATFORM INFORMATION",
            [
                ("system", platform.system()),
                ("platform info", platform.platform()),
                ("release", platform.release()),
                ("processor", platform.processor() or platform.machine()),
            ],
        ),
        (
            "LAUNCHKIT",
            [
                ("version", _version("launchkit")),
                ("python", f"{platform.python_version()} ({sys.executable})"),
                ("rclpy", "{} ({})".format(*rclpy_choice())),
            ],
        ),
        (
            "MIDDLEWARE",
            [
                ("transport", "zenoh " + _version("eclipse-zenoh")),
                ("wire format", "rmw_zenoh (Jazzy)"),
                ("RMW_IMPLEMENTATION", os.environ.get("RMW_IMPLEMENTATION", "") or "not set"),
                ("router", f"{endpoint} ({'answers' if up else 'nothing answers'})"),
                ("ROS_DOMAIN_ID", os.environ.get("ROS_DOMAIN_ID", "") or "0 (not set)"),
            ],
        ),
    ]
    if not exclude_packages:
        names = PackageIndex().names()
        out.append(
            (
                "PACKAGES",
                [
                    ("AMENT_PREFIX_PATH", os.environ.get("AMENT_PREFIX_PATH", "") or "not set"),
                    ("packages", str(len(names))),
                ],
            )
        )
    out.append(("TOPIC LIST", _topic_items(endpoint) if up else [("topic", "none")]))
    return out


def _topic_items(endpoint: str) -> list[tuple[str, str]]:
    from launchkit.ros.graph import snapshot
    from launchkit.ros.session import client_config, close_session, open_session

    session = open_session(client_config(endpoint))
    try:
        tokens = snapshot(session, domain_id())
    finally:
        close_session(session)
    topics = sorted({t.topic for t in tokens if t.kind in ("MP", "MS")})
    items: list[tuple[str, str]] = []
    for topic in topics:
        items.append(("topic", topic))
        items.append(
            ("publisher count", str(sum(t.kind == "MP" and t.topic == topic for t in tokens)))
        )
        items.append(
            ("subscriber count", str(sum(t.kind == "MS" and t.topic == topic for t in tokens)))
        )
    return items or [("topic", "none")]


def print_report(report: Report) -> None:
    """A report as ros2 doctor prints one: its name, then ``item: value`` lines padded."""
    name, items = report
    print("\n  ", name)
    longest = max(len(item) for item, _ in items)
    width = longest + 4 if longest >= 8 else 8
    for item, value in items:
        print(f"{item:{width}}: {value}")


def _doctor(args: argparse.Namespace) -> int:
    if args.report:
        for report in reports(args.exclude_packages):
            print_report(report)
        return 0
    failed: list[str] = []
    for category, check in CHECKS.items():
        if category == "packages" and args.exclude_packages:
            continue
        errors, warnings = check()
        for message in errors:
            print(f"{category}: ERROR: {message}", file=sys.stderr)
        for message in warnings:
            print(f"{category}: WARNING: {message}", file=sys.stderr)
        if errors or (args.include_warnings and warnings):
            failed.append(category)
    total = len(CHECKS) - (1 if args.exclude_packages else 0)
    if failed:
        print(f"\n{len(failed)}/{total} check(s) failed\n")
        print("Failed modules:", *failed)
    else:
        print(f"\nAll {total} checks passed\n")
    if args.report_failed and failed:
        wanted = {_REPORT_OF[category] for category in failed}
        for report in reports(args.exclude_packages):
            if report[0] in wanted:
                print_report(report)
    return 0


#: the report that shows what each check looked at (``--report-failed``)
_REPORT_OF = {
    "router": "MIDDLEWARE",
    "domain": "MIDDLEWARE",
    "middleware": "MIDDLEWARE",
    "rclpy": "LAUNCHKIT",
    "packages": "PACKAGES",
}
