"""launchkit's Python API: find, check, describe and run launch files (the CLI calls these)."""

from __future__ import annotations

import os
import sys
import sysconfig
import threading
from collections.abc import Mapping
from pathlib import Path
from typing import IO, TYPE_CHECKING

from launchkit.bridge.launch import add_bridge
from launchkit.checks import CheckedTree, check_tree, static_path, undeclared_arguments
from launchkit.description.actions import DeclareArgument, Include
from launchkit.description.actions.base import Action
from launchkit.description.launch_context import LaunchContext, Runner
from launchkit.description.launch_description import LaunchDescription
from launchkit.description.ros_link import RosLink
from launchkit.errors import LaunchkitError, PackageNotFoundError, UserError
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.packages import PackageIndex, is_file
from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.logdir import create_run_dir
from launchkit.runtime.recorder import Recorded, Recorder, count, render
from launchkit.runtime.signals import held, raising

if TYPE_CHECKING:
    from launchkit.ros_adapter.lockstep import ClockOptions, LaunchClock
    from launchkit.runtime.network import NodeNetwork, RouterOptions
    from launchkit.runtime.supervisor import Supervisor


def resolve_launch_file(target: str, filename: str | None, packages: PackageIndex) -> Path:
    """``launchkit run PKG FILE`` or ``launchkit run FILE``: the launch file's path.

    A bare FILE that is not in the current directory is looked up in every known package's
    launch folders; several matches are an error listing them.
    """
    if filename is not None:
        return packages.launch_file(target, filename)
    path = Path(target).expanduser()
    if is_file(path):
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


def lockstep_options(
    *, rtf: float | None = None, until: float | None = None, paused: bool = False
) -> ClockOptions:
    """How ``run(..., lockstep=...)`` runs the launch's simulated clock: at most ``rtf`` times
    real time (None: as fast as the nodes allow), ending the launch at ``until`` simulated
    seconds, or ``paused`` until a test asks for time (``launchkit.testing``)."""
    from launchkit.ros_adapter.lockstep import ClockOptions

    return ClockOptions(rtf=rtf, until=until, paused=paused)


def _start_clock(
    clock: LaunchClock, supervisor: Supervisor, network: NodeNetwork, context: LaunchContext
) -> None:
    """Start a lockstep launch's clock on its router (started now, before any process)."""
    from launchkit.runtime.network import ROUTER_ENV

    def log(level: str, message: str) -> None:  # the clock's thread: on the loop
        context.post(lambda: supervisor.log(level, "lockstep", message))

    def until() -> None:
        context.post(lambda: supervisor.begin_shutdown("the simulated time is up (--until)"))

    clock.start(network.ensure(supervisor)[ROUTER_ENV], log, until)


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
            run = create_run_dir(os.environ)
            run.release()  # nothing runs (--print): later runs may prune it
            log_dir = run.path
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
    ``Command(['xacro ', ...])`` works from an environment that was not activated; and after it
    a ``ros2`` for launch files that call one, when none is installed
    (:mod:`launchkit.ros_cli.ros2_shim`)."""
    from launchkit.ros_cli.ros2_shim import with_ros2

    environment = dict(environ)
    scripts = sysconfig.get_path("scripts")
    folders = environment.get("PATH", os.defpath).split(os.pathsep)
    if scripts and scripts not in folders:
        environment["PATH"] = os.pathsep.join([*folders, scripts])
    return with_ros2(environment)


def dry_run(
    path: Path, arguments: Mapping[str, str] | None = None, *, bridge: bool = False
) -> tuple[CheckedTree, list[Recorded]]:
    """Check ``path``, then evaluate it as running it would, starting nothing: every included
    file is loaded, every package and executable looked up, every ``$(command)`` run. What it
    would start is recorded (timers' actions at once); errors are raised as ``run`` raises
    them. ``bridge`` adds ``launchkit bridge`` as ``run(bridge=True)`` does."""
    arguments = dict(arguments or {})
    packages, loader = PackageIndex(), LaunchLoader()
    tree = check_tree(path, arguments, loader, packages)
    if bridge:
        add_bridge(tree.top, arguments)
    recorder = Recorder()
    context = _context(recorder, arguments, packages, loader, None)
    recorder.context = context
    context.uninterrupted = held
    context.delivers_events = False  # nothing drains them: handlers' actions are recorded
    try:
        with raising(), context.in_file(tree.top.path):
            for action in tree.top.actions:
                action.visit(context)
        return tree, recorder.items
    finally:
        context.cleanup()


def describe(
    path: Path, arguments: Mapping[str, str] | None = None, *, bridge: bool = False
) -> str:
    """What running ``path`` would do (processes with command lines, env changes, timers)."""
    return render(dry_run(path, arguments, bridge=bridge)[1])


def check_report(path: Path, arguments: Mapping[str, str] | None = None) -> str:
    """``launchkit check``: check ``path`` and evaluate it as ``--print`` does (packages,
    included files, commands), then say what was checked and what was not."""
    tree, items = dry_run(path, arguments)
    processes, timers = count(items)
    report = (
        f"{path}: ok ({len(tree.files)} file(s), {tree.entity_count} entities; "
        f"with these arguments it starts {processes} process(es)"
        + (f" and {timers} timer(s)" if timers else "")
        + ")"
    )
    if tree.has_conditions():
        report += (
            "\nnot checked: what an if/unless that is false with these arguments would "
            "include or start (pass other arguments to check it)"
        )
    return report


def show_arguments(path: Path) -> str:
    """The arguments ``path`` and the files it includes declare (first declaration wins, as
    ``ros2 launch --show-args``), with defaults, descriptions and choices."""
    packages = PackageIndex()
    tree = check_tree(path, None, LaunchLoader(), packages)
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    declared = _declared_arguments(tree, packages)
    if not declared:
        lines.append("\n  No arguments.")
    for arg, conditional in declared:
        lines.append(f"\n    '{arg.name}':")
        lines.append(f"        {arg.description or 'no description given'}")
        if arg.choices:
            lines.append("        Valid choices are: " + ", ".join(repr(c) for c in arg.choices))
        default = arg.describe_default()
        lines.append(
            f"        (default: {default!r})" if default is not None else "        (required)"
        )
        if conditional:
            lines.append("        (declared conditionally)")
    return "\n".join(lines)


def _declared_arguments(
    tree: CheckedTree, packages: PackageIndex
) -> list[tuple[DeclareArgument, bool]]:
    """Every ``<arg>`` of the top file and of the files it includes statically, in document
    order (an included file's where its ``<include>`` is), each with whether an ``if`` or
    ``unless`` on it or around it decides whether it is declared at all."""
    found: dict[str, tuple[DeclareArgument, bool]] = {}

    def visit(description: LaunchDescription, actions: list[Action], conditional: bool) -> None:
        for action in actions:
            guarded = conditional or action.condition is not None
            if isinstance(action, DeclareArgument):
                found.setdefault(action.name, (action, guarded))
            elif isinstance(action, Include):
                included = static_path(action, description.path, packages)
                child = tree.files.get(included) if included is not None else None
                if child is not None and child.path not in visiting:
                    visiting.add(child.path)
                    visit(child, child.actions, guarded)
                    visiting.discard(child.path)
            visit(description, list(action.children()), guarded)

    visiting = {tree.top.path}
    visit(tree.top, tree.top.actions, False)
    return list(found.values())


def run(
    path: Path,
    arguments: Mapping[str, str] | None = None,
    *,
    stream: IO[str] | None = None,
    router: str | None = None,
    router_options: RouterOptions | None = None,
    hooks: SupervisorHooks | None = None,
    bridge: bool = False,
    agent_key: str | None = None,
    remote_grace: str | None = None,
    lockstep: ClockOptions | None = None,
) -> int:
    """Run ``path`` until everything it started has stopped; the exit status.

    User mistakes found before anything starts raise :class:`launchkit.errors.UserError`.
    ``hooks`` observes the launch as it runs (the test plugin's event channel uses it).
    ``bridge`` also runs ``launchkit bridge`` (to a ROS 2 DDS graph) under supervision.
    ``router_options``: what the launch's router adds to reach other hosts (default: the
    ``LAUNCHKIT_ROUTER_*`` variables). ``agent_key`` and ``remote_grace`` (seconds) are for the
    processes that ``<group machine=...>`` puts on other hosts (``docs/multi-host.md``).
    ``lockstep`` runs every node on the launch's simulated clock (``docs/simulation.md``).

    Call it from the main thread (it handles SIGINT and SIGTERM, which Python delivers only
    there); from another thread it raises :class:`UserError` before it creates anything.
    """
    if threading.current_thread() is not threading.main_thread():
        raise UserError(
            "launchkit.run() was called from a thread other than the main thread",
            expected="a call from the main thread, which alone receives signals (Ctrl-C)",
            hint="to launch from a worker thread, start `launchkit run FILE` as a subprocess",
        )
    # what only running needs (the supervisor, its output, the router, other hosts): imported
    # here, as a check never runs anything (about 6 % of checking the seed's launch file)
    from launchkit.remote.launch import RemoteLaunch
    from launchkit.runtime.logdir import LogLimits
    from launchkit.runtime.network import NodeNetwork
    from launchkit.runtime.output import Output
    from launchkit.runtime.supervisor import Supervisor

    arguments = dict(arguments or {})
    clock: LaunchClock | None = None
    network = NodeNetwork(router, router_options)
    remote = RemoteLaunch(network, agent_key, remote_grace)
    packages, loader = PackageIndex(), LaunchLoader()
    limits = LogLimits.from_environment(os.environ)
    # As ros2 launch: the run folder exists (and `latest` points at it) even when the file is
    # rejected; its launch.log then holds the error.
    run_dir = create_run_dir(os.environ, limits.keep_runs)
    output = Output(stream or sys.stdout)
    output.open_logs(run_dir.path, limits)
    try:
        tree = check_tree(path, arguments, loader, packages)
        if bridge:
            add_bridge(tree.top, arguments)
        output.launch_line("INFO", "launch", f"All log files can be found below {run_dir.path}")
        for name in undeclared_arguments(tree, arguments):
            output.launch_line(
                "WARNING",
                "launch",
                f"argument '{name}' is not declared or used by "
                f"{path.name} (or the files it includes statically)",
            )
        if lockstep is not None:
            from launchkit.ros_adapter.lockstep import LaunchClock
            from launchkit.runtime.clock_hooks import ClockHooks

            clock = LaunchClock(lockstep)
            hooks = ClockHooks(clock, hooks)
            network.lockstep = True
        supervisor = Supervisor(output, network=network, hooks=hooks, remote_factory=remote.factory)
        remote.bind(supervisor)
        context = _context(supervisor, arguments, packages, loader, run_dir.path)
        if clock is not None:
            _start_clock(clock, supervisor, network, context)

        def ros_link() -> RosLink:
            # imported when a lifecycle or composable node first needs the launcher's own ROS
            # node: the ROS layer (numpy, zenoh, the message types) is most of a second
            from launchkit.ros_adapter import RosAdapter

            return RosAdapter(lambda: network.ensure(supervisor), context.post)

        context.ros_factory = ros_link
        return supervisor.run(tree.top, context)
    except LaunchkitError as error:
        output.launch_error(error.format(), screen=False)
        raise
    finally:
        if clock is not None:
            clock.close()
        remote.close()
        output.close()
        run_dir.release()
