"""The state actions read and change while a launch description executes.

A :class:`Scope` holds what ``<group>`` pushes and pops: launch configurations (including
``ros_namespace``), the environment, global ROS parameters and remaps. :class:`LaunchContext`
adds what lives for the whole run: the package index, anonymous names, the log directory, the
launch file being executed, and the :class:`Runner` that starts processes and timers.

This module is the bottom of the description package: it knows actions, timers and loaded
launch files only by the protocols below (what it hands around), so nothing it imports
imports it back.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from launchkit.packages import PackageIndex

if TYPE_CHECKING:
    from launchkit.description.process_spec import ProcessSpec
    from launchkit.description.ros_link import RosLink
    from launchkit.errors import LaunchkitError, Location


@dataclass
class Scope:
    """What a scoped ``<group>`` saves and restores."""

    configurations: dict[str, str] = field(default_factory=dict)
    environment: dict[str, str] = field(default_factory=dict)
    # (name, value) from <set_parameter>, a file path from <set_parameters_from_file>, in order
    global_params: list[tuple[str, str] | str] = field(default_factory=list)
    remaps: list[tuple[str, str]] = field(default_factory=list)
    machine: str = ""  # ``<group machine>``: the host its processes run on ("" for this one)

    def copy(self) -> Scope:
        """An independent copy (what a timer captures): new containers; what they hold
        (strings and tuples of strings) cannot change."""
        return Scope(
            dict(self.configurations),
            dict(self.environment),
            list(self.global_params),
            list(self.remaps),
            self.machine,
        )


class Visitable(Protocol):
    """An action as the context sees it (:class:`launchkit.description.actions.base.Action`)."""

    def visit(self, context: LaunchContext) -> None:
        """Run the action in ``context`` (unless its condition says not to)."""


class DelayedActions(Protocol):
    """Actions to run later, in a captured scope (a ``<timer>``)."""

    @property
    def actions(self) -> Sequence[Visitable]:
        """What runs when the delay is over."""

    @property
    def cancel_on_shutdown(self) -> bool:
        """Whether a shutdown drops them before they run."""


class Handler(Protocol):
    """An event handler as the context keeps it
    (:class:`launchkit.description.events.EventHandler`)."""

    snapshot: Snapshot | None

    def matches(self, event: object) -> bool:
        """Whether it reacts to ``event``."""

    def handle(self, event: object, context: LaunchContext) -> Sequence[Visitable]:
        """The actions to run for ``event``."""

    @property
    def handle_once(self) -> bool:
        """Whether it is unregistered after its first event."""


class RequiredArgument(Protocol):
    """An ``<arg>`` without a default, as an include checks it."""

    @property
    def name(self) -> str:
        """The argument's name."""

    def missing_error(self) -> LaunchkitError:
        """The error for the argument not being given."""


class LoadedFile(Protocol):
    """A loaded launch file, as ``<include>`` runs it
    (:class:`launchkit.description.launch_description.LaunchDescription`)."""

    @property
    def actions(self) -> Sequence[Visitable]:
        """The file's actions in document order."""

    def required_arguments(self) -> Sequence[RequiredArgument]:
        """The arguments the file needs from its includer."""


class Runner(Protocol):
    """Whoever runs the launch, as executing actions sees it: the supervisor, or the recorder
    behind ``--print``."""

    def start_process(self, spec: ProcessSpec) -> None:
        """Start (or, while recording, list) a process."""

    def schedule_timer(self, period: float, timer: DelayedActions, snapshot: Snapshot) -> None:
        """Run the timer's actions after ``period`` seconds in the captured scope."""

    def request_shutdown(self, reason: str) -> None:
        """Shut the launch down (``<shutdown>``)."""

    def log(self, level: str, logger: str, message: str) -> None:
        """Print a launch line ``[LEVEL] [logger]: message``."""

    def stop_processes(self, matcher: Callable[[object], bool], signum: int | None) -> None:
        """Stop (``signum`` None: as a shutdown would, never respawning) or signal the running
        processes whose action ``matcher`` accepts."""


class ChildGroups(Protocol):
    """Who must know the process groups that evaluation starts (a ``$(command)``), so that
    they die with the launcher however it ends (the runtime's orphan guard)."""

    def watch(self, pgid: int) -> None:
        """``pgid`` exists now."""

    def forget(self, pgid: int) -> None:
        """``pgid`` is gone (its id may be reused)."""


@dataclass(frozen=True)
class Snapshot:
    """A scope and file captured for later (timers run their actions in it)."""

    scope: Scope
    current_file: Path | None


#: Loads the launch file at a path (the location is the ``<include>`` that asks, for errors;
#: the syntax is None to go by the file's suffix, or the one the include asks for).
Loader = Callable[[Path, "Location | None", "str | None"], LoadedFile]


class LaunchContext:
    """Scopes, the current file and the run-wide services actions use."""

    def __init__(
        self,
        *,
        packages: PackageIndex,
        runner: Runner,
        loader: Loader,
        environment: dict[str, str],
        log_dir: Callable[[], Path],
        configurations: dict[str, str] | None = None,
    ) -> None:
        self.packages = packages
        self.runner = runner
        self.loader = loader
        self.initial_environment = dict(environment)
        self.scope = Scope(configurations=dict(configurations or {}), environment=environment)
        self.current_file: Path | None = None
        #: the files whose actions are being visited, outermost first (an include cycle)
        self.open_files: list[Path] = []
        self.anon_names: dict[str, str] = {}
        self._log_dir = log_dir
        self._stack: list[Scope] = []
        self._scratch: Path | None = None
        #: Registered event handlers, newest first (as ROS keeps them).
        self.handlers: deque[Handler] = deque()
        self.event_queue: deque[object] = deque()
        #: Whether anything drains the queue: False for ``--print`` and ``check``, whose
        #: events would never reach a handler, so none is built or queued (a large file
        #: would queue one per action).
        self.delivers_events = True
        self.draining = False
        self.is_shutdown = False
        self.locals: dict[str, Any] = {}
        #: What Push/PopLaunchConfigurations and Push/PopEnvironment (Python API) keep.
        self.saved_scopes: list[Scope] = []
        self.saved_environments: list[dict[str, str]] = []
        #: Told of every handler registered (the ``--print`` recorder shows their actions).
        self.on_register: Callable[[Handler], None] | None = None
        #: Set by ``--print`` and ``check`` while they show an event handler's actions, which
        #: ROS runs only when the event comes: an action that would call the launch file's own
        #: code (an OpaqueFunction, a handler's function) reports what it would call through
        #: this, with where, instead of calling it. None: call it.
        self.instead_of_calling: Callable[[str, Location | None], None] | None = None
        #: Work posted from other threads (the ROS link's replies), run on the launch's loop;
        #: ``waker`` makes the loop look (set by the runner).
        self.posted: deque[Callable[[], None]] = deque()
        self.waker: Callable[[], None] | None = None
        #: Makes the launcher's ROS node on first use (None: no ROS, as for ``--print``).
        self.ros_factory: Callable[[], RosLink] | None = None
        self._ros: RosLink | None = None
        #: set by the supervisor: told about every ``$(command)``'s process group
        self.child_groups: ChildGroups | None = None
        #: set by whoever makes signals interrupt evaluation (the supervisor, ``--print``): a
        #: body a signal must not cut in half (a ``$(command)`` being started and watched);
        #: a signal arriving in it is raised at its end instead
        self.uninterrupted: Callable[[], AbstractContextManager[None]] = nullcontext
        #: set by the supervisor: makes (on the first call) the private folder generated files
        #: go in (removed even when the launcher is killed); None: the system's temporary folder
        self.scratch_root: Callable[[], Path] | None = None

    @property
    def configurations(self) -> dict[str, str]:
        """Launch configurations of the current scope."""
        return self.scope.configurations

    @property
    def environment(self) -> dict[str, str]:
        """Environment of the current scope (what a process started now inherits)."""
        return self.scope.environment

    @property
    def log_dir(self) -> Path:
        """This run's log directory."""
        return self._log_dir()

    def write_scratch_file(self, prefix: str, suffix: str, text: str) -> Path:
        """Write a generated file (a node's parameters) that lives as long as the run."""
        if self._scratch is None:
            root = self.scratch_root() if self.scratch_root is not None else None
            self._scratch = Path(tempfile.mkdtemp(prefix="launchkit-", dir=root))
        handle, name = tempfile.mkstemp(prefix=prefix, suffix=suffix, dir=self._scratch)
        with os.fdopen(handle, "w") as stream:
            stream.write(text)
        return Path(name)

    def cleanup(self) -> None:
        """Leave the ROS graph and remove the generated files."""
        if self._ros is not None:
            self._ros.close()
            self._ros = None
        if self._scratch is not None:
            shutil.rmtree(self._scratch, ignore_errors=True)
            self._scratch = None

    def log(self, level: str, message: str, logger: str = "launch") -> None:
        """Print a launch line through the runner."""
        self.runner.log(level, logger, message)

    def post(self, work: Callable[[], None]) -> None:
        """Run ``work`` on the launch's loop soon (callable from any thread)."""
        self.posted.append(work)
        if self.waker is not None:
            self.waker()

    def ros(self) -> RosLink | None:
        """The launcher's ROS node (made on first use), or None when the launch has none."""
        if self._ros is None and self.ros_factory is not None:
            self._ros = self.ros_factory()
        return self._ros

    def emit(self, event: object) -> None:
        """Queue ``event`` for the handlers (the runner drains the queue); dropped when
        nothing drains it."""
        if self.delivers_events:
            self.event_queue.append(event)

    def register_handler(self, handler: Handler) -> None:
        """Add an event handler, ahead of the ones registered before it; it will run its
        actions in the current scope."""
        handler.snapshot = self.snapshot()
        self.handlers.appendleft(handler)
        if self.on_register is not None:
            self.on_register(handler)

    @contextmanager
    def local(self, name: str, value: Any) -> Iterator[None]:
        """Make ``value`` the local ``name`` (``LocalSubstitution``) while the body runs."""
        missing = object()
        previous = self.locals.get(name, missing)
        self.locals[name] = value
        try:
            yield
        finally:
            if previous is missing:
                self.locals.pop(name, None)
            else:
                self.locals[name] = previous

    @contextmanager
    def scoped(self, scope: Scope | None = None) -> Iterator[None]:
        """Run the body in a copy of the current scope (or in ``scope``), then restore."""
        self._stack.append(self.scope)
        self.scope = scope if scope is not None else self.scope.copy()
        try:
            yield
        finally:
            self.scope = self._stack.pop()

    @contextmanager
    def in_file(self, path: Path, *, opened: bool = True) -> Iterator[None]:
        """Run the body as if written in ``path`` (``$(dirname)``, relative includes);
        ``opened``: the body visits the file's actions (not a timer's, later)."""
        previous, self.current_file = self.current_file, path
        if opened:
            self.open_files.append(path)
        try:
            yield
        finally:
            self.current_file = previous
            if opened:
                self.open_files.pop()

    def snapshot(self) -> Snapshot:
        """Capture the scope and file for a timer."""
        return Snapshot(self.scope.copy(), self.current_file)

    @contextmanager
    def restored(self, snapshot: Snapshot) -> Iterator[None]:
        """Run the body in a captured scope and file."""
        with (
            self.scoped(snapshot.scope.copy()),
            self.in_file(snapshot.current_file or Path(), opened=False),
        ):
            if snapshot.current_file is None:
                self.current_file = None
            yield
