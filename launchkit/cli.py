"""The ``launchkit`` command line: argument parsing only; the work is in :mod:`launchkit.api`.

Exit status: 0 when all went well (a launch stopped with Ctrl-C included, as ``ros2 launch``),
2 for a user mistake (reported as one ``FILE:LINE:COL: error: ...`` line before anything
starts), 1 for a failure while running (or the exit code of an ``on_exit="shutdown"`` process
that failed), 128 + N for a launch stopped by SIGTERM, SIGHUP or SIGQUIT, or for any command
a signal interrupted (130 for Ctrl-C while parsing or ``--print``).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from launchkit._argparse import CommandParser
from launchkit._exit import exit_promptly
from launchkit.errors import LaunchkitError, UserError, printable

if TYPE_CHECKING:
    from launchkit.runtime.hooks import SupervisorHooks

#: ``ros2``'s verbs that ``launchkit.ros_cli`` implements (``launchkit <verb> ...``), and
#: launchkit's own ``router`` and ``tf``
ROS_COMMANDS = (
    "topic",
    "node",
    "service",
    "param",
    "interface",
    "pkg",
    "doctor",
    "wtf",
    "router",
    "tf",
    "action",
)


def _launch_parser(prog: str, description: str) -> CommandParser:
    parser = CommandParser(prog=prog, description=description)
    parser.add_argument(
        "items",
        nargs="+",
        metavar="[PKG] FILE [name:=value ...]",
        help="a launch file (a path, or a file name found in the packages' launch folders), "
        "optionally preceded by its package, then launch arguments",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    return parser


def _add_launch_command(commands: Any, name: str, help_text: str) -> None:
    """``launchkit run`` and its ros2 spelling ``launchkit launch``: the same command."""
    run = commands.add_parser(
        name,
        help=help_text,
        add_help=False,
        parents=[_launch_parser(f"launchkit {name}", "Run a launch file.")],
    )
    run.add_argument(
        "-p",
        "--print",
        action="store_true",
        dest="print_description",
        help="print what would run (command lines, env, timers) and run nothing",
    )
    run.add_argument(
        "-s",
        "--show-args",
        action="store_true",
        help="list the launch file's arguments and run nothing",
    )
    run.add_argument(
        "-a",
        "--show-all-subprocesses-output",
        action="store_true",
        help='show every process\'s output on the screen (output="both")',
    )
    run.add_argument("--router", help="Zenoh router endpoint to host or join (tcp/HOST:PORT)")
    from launchkit.ros_cli.router_options import add_federation_options

    add_federation_options(run)
    remote = run.add_argument_group('processes on other hosts (<group machine="NAME">)')
    remote.add_argument(
        "--agent-key", metavar="FILE", help="the agents' key (default $LAUNCHKIT_AGENT_KEY)"
    )
    remote.add_argument(
        "--remote-grace",
        metavar="SECONDS",
        help="how long agents keep this launch's processes once they lost it "
        "(default $LAUNCHKIT_REMOTE_GRACE or 10)",
    )
    run.add_argument(
        "--bridge",
        action="store_true",
        help="also run `launchkit bridge` to the ROS 2 (DDS) graph (needs launchkit[ros2])",
    )
    sim = run.add_argument_group("simulated time (docs/simulation.md)")
    sim.add_argument(
        "--lockstep",
        action="store_true",
        help="run every node on the launch's simulated clock, which advances only when all are "
        "done with the current instant (repeatable runs, as fast as they allow)",
    )
    sim.add_argument(
        "--rtf",
        type=float,
        metavar="X",
        help="with --lockstep: at most X simulated seconds per wall second (1.0: real time)",
    )
    sim.add_argument(
        "--until",
        type=float,
        metavar="S",
        help="with --lockstep: end the launch (status 0) after S simulated seconds",
    )
    # launchkit.testing's lockstep handles: the time advances only when the test asks
    sim.add_argument("--lockstep-paused", action="store_true", help=argparse.SUPPRESS)
    # launchkit.testing's event channel (launchkit/runtime/events.py): not for people
    run.add_argument("--events-fd", type=int, help=argparse.SUPPRESS)


def build_parser() -> argparse.ArgumentParser:
    """The top-level parser (the ROS commands are parsed by ``launchkit.ros_cli.main``)."""
    parser = CommandParser(
        prog="launchkit", description="Run ROS 2 XML launch files without a ROS install."
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, what in (("run", "run a launch file"), ("launch", "run a launch file (ros2's name)")):
        _add_launch_command(commands, name, what)
    commands.add_parser(
        "check",
        help="check a launch file as --print would (packages, includes, commands); run nothing",
        add_help=False,
        parents=[_launch_parser("launchkit check", "Check a launch file as --print would.")],
    )
    exec_ = commands.add_parser(
        "exec",
        help="run one executable of a package (ros2 run; `launchkit run PKG EXEC` too), or a "
        "Python file with --python",
        usage="launchkit exec [--prefix CMD] PACKAGE EXECUTABLE [ARGS...]\n"
        "       launchkit exec --python FILE [ARGS...]",
    )
    exec_.add_argument(
        "--prefix", help="a command to run it under, in quotes (e.g. --prefix 'gdb -ex run --args')"
    )
    exec_.add_argument("package")
    exec_.add_argument("executable")
    exec_.add_argument("args", nargs=argparse.REMAINDER)
    commands.add_parser("bridge", help="bridge to a ROS 2 DDS graph (see launchkit bridge --help)")
    commands.add_parser(
        "agent", help="run this host's share of launches on other hosts (launchkit agent --help)"
    )
    special = {
        "pkg": "packages: list, prefix, executables, xml (see launchkit pkg --help)",
        "doctor": "check the ROS setup, as ros2 doctor (see launchkit doctor --help)",
        "wtf": "the same as doctor",
    }
    for name in ROS_COMMANDS:
        what = special.get(name, f"ROS {name} tools (see launchkit {name} --help)")
        commands.add_parser(name, help=what, add_help=False)
    commands.add_parser("bag", help="record and play rosbag2 bags (see launchkit bag --help)")
    commands.add_parser(
        "build", help="build a ROS 2 workspace's src/ into install/ (see launchkit build --help)"
    )
    commands.add_parser(
        "shell-init",
        help='a `ros2` command for your shell: eval "$(launchkit shell-init)" (see docs/ros.md)',
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``launchkit`` console script."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] in ROS_COMMANDS:
        return _guarded(lambda: _ros_command(argv[0], argv[1:]), debug="--debug" in argv)
    if argv and argv[0] == "agent":
        from launchkit.remote.cli import main as agent_main

        return _guarded(lambda: agent_main(argv[1:]), debug="--debug" in argv)
    if argv and argv[0] == "bridge":
        from launchkit.bridge.cli import main as bridge_main

        return _guarded(lambda: bridge_main(argv[1:]), debug="--debug" in argv)
    if argv and argv[0] == "bag":
        return _guarded(lambda: _bag_command(argv[1:]), debug="--debug" in argv)
    if argv and argv[0] == "build":
        from launchkit.workspace.cli import main as build_main

        return _guarded(lambda: build_main(argv[1:]), debug="--debug" in argv)
    if argv and argv[0] == "run" and _runs_an_executable(argv[1:]):
        argv = ["exec", *argv[1:]]  # ros2 run's spelling: launchkit run PKG EXEC [args]
    if argv[:2] == ["exec", "--python"]:
        return _guarded(lambda: _exec_python(argv[2:]), debug=False)
    args = build_parser().parse_args(argv)
    if args.command is None:
        build_parser().print_help()
        return 2
    return _guarded(lambda: _dispatch(args), debug=getattr(args, "debug", False))


def console_main() -> NoReturn:
    """The ``launchkit`` console script: :func:`main`, then a prompt exit with its status (the
    interpreter's own teardown would delay the exit by up to seconds on a busy machine; see
    :mod:`launchkit._exit`)."""
    exit_promptly(main())


def _guarded(action: object, debug: bool) -> int:
    try:
        return action()  # type: ignore[operator,no-any-return]
    except LaunchkitError as error:
        if debug:
            import traceback

            traceback.print_exc()
        print(error.format(), file=sys.stderr)
        return error.exit_status
    except KeyboardInterrupt as interrupt:  # launchkit's Interrupted says which signal
        return 128 + getattr(interrupt, "signum", signal.SIGINT)
    except BrokenPipeError:
        # the reader went away (`launchkit run FILE --print | head`): stop writing, quietly, with
        # the status a shell gives a program killed by SIGPIPE
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 128 + signal.SIGPIPE


def _ros_command(command: str, argv: list[str]) -> int:
    from launchkit.ros_cli.main import main as ros_main

    return int(ros_main(command, argv))


def _bag_command(argv: list[str]) -> int:
    from launchkit.bag.cli import main as bag_main

    return bag_main(argv)


def _dispatch(args: argparse.Namespace) -> int:
    from launchkit.packages import PackageIndex

    if args.command == "shell-init":
        from launchkit.ros_cli.ros2_shim import shell_init

        print(shell_init())
        return 0
    if args.command == "exec":
        return _exec(args, PackageIndex())
    if getattr(args, "events_fd", None) is not None:
        return _run_with_events(args, args.events_fd)
    return _launch(args)


def _run_with_events(args: argparse.Namespace, fd: int) -> int:
    """``launchkit run`` that also streams its events to a test process (launchkit.testing)."""
    from launchkit.runtime.events import EventWriter

    try:
        events = EventWriter.from_fd(fd)
    except OSError as error:
        raise UserError(f"--events-fd {fd}: {error.strerror}", expected="an open socket") from None
    try:
        return _launch(args, events)
    except LaunchkitError as error:
        events.launch_failed(error.format())
        raise
    finally:
        events.close()


def _launch(args: argparse.Namespace, hooks: SupervisorHooks | None = None) -> int:
    from launchkit import api
    from launchkit.checks import parse_launch_arguments
    from launchkit.packages import PackageIndex

    items = args.items
    if ":=" in items[0]:
        raise UserError(
            "launch file arguments are out of order",
            expected="[PKG] FILE followed by name:=value items",
        )
    # FILE or PKG FILE, then arguments: any other item is a malformed argument
    with_package = len(items) > 1 and ":=" not in items[1] and not _names_a_file(items[0])
    files = items[: 2 if with_package else 1]
    arguments = parse_launch_arguments(items[len(files) :])
    packages = PackageIndex()
    path = api.resolve_launch_file(files[0], files[1] if with_package else None, packages)
    try:
        if args.command == "check":
            _print(api.check_report(path, arguments))
            return 0
        if args.show_args:
            _print(api.show_arguments(path))
            return 0
        if args.print_description:
            _print(api.describe(path, arguments, bridge=args.bridge))
            return 0
    except LaunchkitError as error:
        error.exit_status = 2  # as for `run`: found before anything would start
        raise
    if args.show_all_subprocesses_output:
        os.environ["OVERRIDE_LAUNCH_PROCESS_OUTPUT"] = "both"
    from launchkit.own_process import become_subreaper
    from launchkit.ros_cli.router_options import federation_asked, federation_options

    options = federation_options(args) if federation_asked(args) else None
    lockstep = _lockstep_options(args)
    # this process is the launch's: what its processes orphan is re-parented here, to be
    # found and killed (launchkit.runtime.containment)
    become_subreaper()
    try:
        return api.run(
            path,
            arguments,
            router=args.router,
            router_options=options,
            hooks=hooks,
            bridge=args.bridge,
            agent_key=args.agent_key,
            remote_grace=args.remote_grace,
            lockstep=lockstep,
        )
    except LaunchkitError as error:
        error.exit_status = 2  # raised before anything started: the input is at fault
        raise


def _lockstep_options(args: argparse.Namespace) -> Any:
    """``--lockstep`` and its options checked (``None`` without it)."""
    from launchkit import api

    paused = args.lockstep_paused
    for flag, value in (("--rtf", args.rtf), ("--until", args.until)):
        if value is not None and not (args.lockstep or paused):
            raise UserError(f"{flag} needs --lockstep", expected=f"--lockstep {flag} ...")
    if args.rtf is not None and not args.rtf > 0:
        raise UserError(f"--rtf {args.rtf:g}", expected="a real-time factor above 0")
    if args.until is not None and not args.until >= 0:
        raise UserError(f"--until {args.until:g}", expected="simulated seconds, 0 or more")
    if not (args.lockstep or paused):
        return None
    return api.lockstep_options(rtf=args.rtf, until=args.until, paused=paused)


def _runs_an_executable(items: list[str]) -> bool:
    """Whether ``launchkit run ITEMS`` is ros2 run's ``run PKG EXEC [args]`` rather than a launch
    file's ``run [PKG] FILE [name:=value]``: ``--prefix`` first, or a package and one of its
    executables that is not also one of its launch files."""
    from launchkit.errors import PackageNotFoundError
    from launchkit.packages import PackageIndex

    if items[:1] == ["--prefix"] or any(item.startswith("--prefix=") for item in items[:1]):
        return True
    if len(items) < 2 or any(i.startswith("-") or ":=" in i for i in items[:2]):
        return False
    package, name = items[0], items[1]
    if _names_a_file(package):
        return False
    index = PackageIndex()
    try:
        index.launch_file(package, name)
        return False
    except PackageNotFoundError:
        pass
    try:
        return name in index.executables(package)
    except PackageNotFoundError:
        return False


def _names_a_file(item: str) -> bool:
    """Whether ``launchkit run ITEM ...`` names a launch file, not a package: an existing file,
    or a name with a dot or a slash, which a package's name never has (REP 144)."""
    from launchkit.packages import is_file

    return is_file(Path(item)) or "." in item or os.sep in item


def _print(report: str) -> None:
    """A report's lines, control characters escaped (names and commands come from files)."""
    print("\n".join(printable(line) for line in report.split("\n")))


def _exec(args: argparse.Namespace, packages: object) -> int:
    """``launchkit exec [--prefix CMD] PKG EXEC [args]`` (ros2 run): this process becomes the
    executable (see :func:`_run_as_child`)."""
    import shlex

    from launchkit.packages import PackageIndex

    assert isinstance(packages, PackageIndex)
    prefix = shlex.split(args.prefix) if args.prefix else []
    _run_as_child(prefix + packages.executable(args.package, args.executable) + list(args.args))
    return 0  # not reached


def _exec_python(argv: list[str]) -> int:
    """``launchkit exec --python FILE [ARGS...]``: a user's own script, with the rclpy that a
    process launchkit starts would get."""
    if not argv or argv[0].startswith("-"):
        raise UserError(
            "exec --python needs a file", expected="launchkit exec --python FILE [ARGS...]"
        )
    if not os.path.isfile(argv[0]):
        raise UserError(f"no file {argv[0]!r}", expected="a Python file to run")
    _run_as_child([sys.executable, *argv])
    return 0  # not reached


def _run_as_child(argv: list[str]) -> None:
    """Replace this process by ``argv``, in the environment launchkit gives its processes: a
    ``ros2`` on its PATH if it has none (:mod:`launchkit.ros_cli.ros2_shim`), and the rclpy
    chosen for it (:mod:`launchkit.ros.face`)."""
    from launchkit.ros.face import child_environment
    from launchkit.ros_cli.ros2_shim import with_ros2

    os.environ.update(with_ros2(os.environ))
    os.environ.update(child_environment(argv, os.environ))
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.stdout.flush()
    try:
        os.execvp(argv[0], argv)  # the executable's path is absolute; a prefix's is looked up
    except OSError as error:
        raise UserError(f"cannot run '{argv[0]}': {error.strerror}") from None


__all__ = ["console_main", "main"]


if __name__ == "__main__":
    raise SystemExit(main())
