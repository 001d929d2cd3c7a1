"""launchkit's Python API: find, check, describe and run launch files (the CLI calls these)."""

from __future__ import annotations

import os
import sys
import sysconfig
from collections.abc import Mapping
from pathlib import Path
from typing import IO

from launchkit.checks import CheckedTree, check_tree, undeclared_arguments
from launchkit.description.launch_context import LaunchContext, Runner
from launchkit.description.ros_link import RosLink
from launchkit.errors import PackageNotFoundError
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.packages import PackageIndex
from launchkit.runtime.hooks import SupervisorHooks


def resolve_launch_file(target: str, filename: str | None, packages: PackageIndex) -> Path:
    """``launchkit run PKG FILE`` or ``launchkit run FILE``: the launch file's path.

    A bare FILE that is not in the current directory is looked up in every known package's
    launch folders; several matches are an error listing them.
    """
    if filename is not None:
        return packages.launch_file(target, filename)
    path = Path(target).expanduser()
    if path.is_file():
        return path.resolve()
    if os.sep in target:
        raise PackageNotFoundError(f"launch file '{target}' does not exist", expected="a file")
    matches = packages.find_launch_file(target)
    if len(matches) == 1:
        return matches[0]
    if not matches:
        raise PackageNotFoundError(
            f"launch file '{target}' not found",
            expected="a file in the current directory or in a package's launch folders",
            hint="searched " + packages.describe_search_path(),
        )
    listing = ", ".join(str(m) for m in matches)
    raise PackageNotFoundError(
        f"launch file '{target}' is in several packages: {listing}",
        expected="PKG FILE to say which",
    )


def check(
    path: Path,
    arguments: Mapping[str, str] | None = None,
    *,
    packages: PackageIndex | None = None,
    loader: LaunchLoader | None = None,
) -> CheckedTree:
    """Parse and check ``path`` (and its static includes) without running anything."""
    return check_tree(path, arguments or {}, loader or LaunchLoader(), packages or PackageIndex())


def _context(
    runner: Runner,
    arguments: Mapping[str, str],
    packages: PackageIndex,
    loader: LaunchLoader,
    log_dir: Path | None,
) -> LaunchContext:
    def run_dir() -> Path:
        nonlocal log_dir
        if log_dir is None:
            from launchkit.runtime.logdir import create_run_dir

            log_dir = create_run_dir(os.environ)
        return log_dir

    return LaunchContext(
        packages=packages,
        runner=runner,
        loader=loader.load,
        environment=launch_environment(os.environ),
        log_dir=run_dir,
        configurations=dict(arguments),
    )


def launch_environment(environ: Mapping[str, str]) -> dict[str, str]:
    """The environment a launch starts with: ``environ``, with the folder of launchkit's own
    scripts (``xacro`` beside ``launchkit``) at the end of ``PATH`` when it is not there, so
    ``Command(['xacro ', ...])`` works from an environment that was not activated."""
    environment = dict(environ)
    scripts = sysconfig.get_path("scripts")
    folders = environment.get("PATH", os.defpath).split(os.pathsep)
    if scripts and scripts not in folders:
        environment["PATH"] = os.pathsep.join([*folders, scripts])
    return environment


def describe(
    path: Path, arguments: Mapping[str, str] | None = None, *, bridge: bool = False
) -> str:
    """What running ``path`` would do (processes with command lines, env changes, timers)."""
    from launchkit.runtime.recorder import Recorder, render

    arguments = dict(arguments or {})
    packages, loader = PackageIndex(), LaunchLoader()
    tree = check_tree(path, arguments, loader, packages)
    if bridge:
        from launchkit.bridge.launch import add_bridge

        add_bridge(tree.top, arguments)
    recorder = Recorder()
    context = _context(recorder, arguments, packages, loader, None)
    recorder.context = context
    try:
        with context.in_file(tree.top.path):
            for action in tree.top.actions:
                action.visit(context)
        return render(recorder.items)
    finally:
        context.cleanup()


def show_arguments(path: Path) -> str:
    """The arguments ``path`` declares, with defaults, descriptions and choices."""
    description = check_tree(path, None, LaunchLoader(), PackageIndex()).top
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    declared = description.declared_arguments()
    if not declared:
        lines.append("\n  No arguments.")
    for arg in declared:
        lines.append(f"\n    '{arg.name}':")
        lines.append(f"        {arg.description or 'no description given'}")
        if arg.choices:
            lines.append("        Valid choices are: " + ", ".join(repr(c) for c in arg.choices))
        default = arg.describe_default()
        lines.append(
            f"        (default: {default!r})" if default is not None else "        (required)"
        )
        if arg.condition is not None:
            lines.append("        (declared conditionally)")
    return "\n".join(lines)


def run(
    path: Path,
    arguments: Mapping[str, str] | None = None,
    *,
    stream: IO[str] | None = None,
    router: str | None = None,
    hooks: SupervisorHooks | None = None,
    bridge: bool = False,
) -> int:
    """Run ``path`` until everything it started has stopped; the exit status.

    User mistakes found before anything starts raise :class:`launchkit.errors.UserError`.
    ``hooks`` observes the launch as it runs (the test plugin's event channel uses it).
    ``bridge`` also runs ``launchkit bridge`` (to a ROS 2 DDS graph) under supervision.
    """
    from launchkit.runtime.logdir import create_run_dir
    from launchkit.runtime.network import NodeNetwork
    from launchkit.runtime.output import Output
    from launchkit.runtime.supervisor import Supervisor

    arguments = dict(arguments or {})
    packages, loader = PackageIndex(), LaunchLoader()
    tree = check_tree(path, arguments, loader, packages)
    if bridge:
        from launchkit.bridge.launch import add_bridge

        add_bridge(tree.top, arguments)
    output = Output(stream or sys.stdout)
    run_dir = create_run_dir(os.environ)
    output.open_logs(run_dir)
    output.launch_line("INFO", "launch", f"All log files can be found below {run_dir}")
    for name in undeclared_arguments(tree, arguments):
        output.launch_line(
            "WARNING",
            "launch",
            f"argument '{name}' is not declared or used by "
            f"{path.name} (or the files it includes statically)",
        )
    network = NodeNetwork(router)
    supervisor = Supervisor(output, network=network, hooks=hooks)
    context = _context(supervisor, arguments, packages, loader, run_dir)

    def ros_link() -> RosLink:
        from launchkit.ros_adapter import RosAdapter

        return RosAdapter(lambda: network.ensure(supervisor), context.post)

    context.ros_factory = ros_link
    try:
        return supervisor.run(tree.top, context)
    finally:
        output.close()
