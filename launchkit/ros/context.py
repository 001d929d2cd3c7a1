"""The process's ROS context: command-line arguments, the Zenoh session, init/ok/shutdown."""

from __future__ import annotations

import atexit
import contextlib
import os
import sys
import threading
import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from launchkit.ros.arguments import RosArguments, parse_ros_args
from launchkit.ros.keyexpr import domain_id as domain_id_from_environment
from launchkit.ros.lockstep.participant import Participant
from launchkit.ros.lockstep.participant import wanted as lockstep_wanted
from launchkit.ros.logging import get_logger
from launchkit.ros.router_access import ForeignRouterError
from launchkit.ros.router_watch import watch_router
from launchkit.ros.session import (
    SESSION_CONFIG_ENV,
    client_config,
    close_all,
    close_session,
    open_session,
    peer_config,
    router_endpoint,
    wait_for_router,
)
from launchkit.ros.shared_router import ensure_router

ROUTER_WAIT = 2.0  # seconds a new session waits for the router before going on without it

if TYPE_CHECKING:
    import zenoh

    from launchkit.ros.graph import Graph


class ContextNode(Protocol):
    """What the context does with the nodes created in it (:class:`launchkit.ros.Node`)."""

    def wake(self) -> None:
        """Make a blocked spin of the node look again."""

    def close_entities(self) -> None:
        """Undeclare the node's entities (the context shuts down)."""


class NotInitializedException(Exception):
    """A ROS entity was made before ``init()`` or after ``shutdown()`` (rclpy's exception)."""

    def __init__(self, message: str | None = None) -> None:
        text = "rclpy.init() has not been called."
        super().__init__(f"{text} msg:{message}" if message else text)


NotInitializedError = NotInitializedException  # launchkit's earlier name


class RCLError(RuntimeError):
    """What rcl reports as an error (rclpy's ``_rclpy_pybind11.RCLError``)."""


class Context:
    """One ROS context: its arguments, domain, Zenoh session and graph (both opened lazily).

    ``shutdown()`` is rclpy's: an error if the context was never initialized or is shut down
    already (by a signal, say); ``try_shutdown()`` is the quiet one.
    """

    def __init__(
        self, router: str | None = None, *, start_router: bool | None = None, client: bool = False
    ) -> None:
        self.router = router  # None: $LAUNCHKIT_ROUTER, else the default endpoint
        # None: $LAUNCHKIT_ROUTER_AUTOSTART decides whether a missing router is started
        self.start_router = start_router
        # a command-line tool's context: its session is a client of the router (see
        # session.client_config), connected when opened
        self.client = client
        self._lock = threading.RLock()
        self._initialized = False
        self._interrupted = False
        self._shutdown_callbacks: list[Callable[[], None]] = []
        self._session: zenoh.Session | None = None
        self._router_watch: Any = None
        #: Set when the session linked to another user's router: nothing is delivered from then
        #: on, the context is interrupted and the process exits 1.
        self.refused: ForeignRouterError | None = None
        self._graph: Graph | None = None
        self._next_id = 0
        self.argv: list[str] = []
        self.ros_args = RosArguments()
        self.domain_id = 0
        self._nodes: weakref.WeakSet[ContextNode] = weakref.WeakSet()
        #: This context's part in a lockstep launch (``launchkit.ros.lockstep``), else None.
        self.lockstep: Participant | None = None

    def init(self, args: list[str] | None = None, domain_id: int | None = None) -> None:
        """Parse ``--ros-args`` and mark the context usable (the session opens on first use)."""
        with self._lock:
            if self._initialized:
                raise RuntimeError("Context.init() must only be called once")
            if domain_id is not None and domain_id < 0:
                raise RuntimeError(f"Domain id ({domain_id}) should not be lower than zero.")
            self.argv = list(sys.argv if args is None else args)
            self.ros_args = parse_ros_args(self.argv)
            self.domain_id = domain_id_from_environment() if domain_id is None else domain_id
            self._interrupted = False
            self._initialized = True
            _contexts.add(self)
        if lockstep_wanted() and self.lockstep is None:
            self.lockstep = Participant(self)

    def ok(self) -> bool:
        """True between ``init()`` and ``shutdown()`` (or a signal)."""
        return self._initialized and not self._interrupted

    def get_domain_id(self) -> int:
        """The ROS domain (``ROS_DOMAIN_ID`` or ``init``'s ``domain_id``)."""
        if not self._initialized:
            raise RuntimeError("Context must be initialized before it can have a domain id")
        return self.domain_id

    def interrupt(self) -> None:
        """Shut down as a signal does: ``ok()`` false and every spinner woken, nothing torn
        down yet.

        Safe in a signal handler: the entities are destroyed later by ``shutdown()`` or
        ``try_shutdown()`` in the thread that owns them (or at exit), never under a running
        callback.
        """
        self._interrupted = True
        for node in list(self._nodes):
            node.wake()

    def require(self, what: str = "cannot create node") -> None:
        """Raise :class:`NotInitializedException` unless the context is usable."""
        if not self._initialized:
            raise NotInitializedException(what)

    @property
    def session(self) -> zenoh.Session:
        """The context's Zenoh session (opened on first use, connected to the router)."""
        with self._lock:
            self.require("cannot use the context")
            if self._session is None:
                endpoint = router_endpoint(self.router)
                if not os.environ.get(SESSION_CONFIG_ENV):  # else the file names the router
                    ensure_router(endpoint, autostart=self.start_router, say=_say)
                config = client_config(self.router) if self.client else peer_config(self.router)
                self._session = open_session(config)
                self._router_watch = watch_router(self._session, endpoint, self._refuse)
                if not wait_for_router(self._session, ROUTER_WAIT):
                    get_logger("launchkit.ros").warn(
                        f"Unable to connect to a ROS router at {endpoint}: this node keeps "
                        "trying (start `launchkit router` or a launch there)"
                    )
            return self._session

    def _refuse(self, error: ForeignRouterError) -> None:  # a Zenoh thread
        """The session linked to another user's router: stop delivering at once, leave it,
        and end the process's work (it exits 1: :func:`exit_status`, ``_at_exit``)."""
        if self.refused is not None:
            return
        self.refused = error
        _refusals.append(error)
        get_logger("launchkit.ros").error(f"after losing its router: {error.message}")
        session = self._session
        if session is not None:  # not from this thread: Zenoh is making the link
            threading.Thread(target=close_session, args=(session,), daemon=True).start()
        self.interrupt()

    @property
    def graph(self) -> Graph:
        """The ROS graph as seen through liveliness tokens (started on first use)."""
        with self._lock:
            if self._graph is None:
                from launchkit.ros.graph import Graph

                self._graph = Graph(self.session, self.domain_id)
            return self._graph

    def next_entity_id(self) -> int:
        """A fresh id for a node or entity (unique in this context)."""
        with self._lock:
            self._next_id += 1
            return self._next_id

    def add_node(self, node: ContextNode) -> None:
        """Track ``node`` so shutdown can wake its executor."""
        self._nodes.add(node)

    def on_shutdown(self, callback: Callable[[], None]) -> None:
        """Call ``callback`` when the context shuts down (at once if it is shut down)."""
        if self._initialized and not self.ok():
            callback()
            return
        self._shutdown_callbacks.append(callback)

    def shutdown(self) -> None:
        """Stop everything: wake spinners, undeclare entities, close the session.

        As rclpy: an error when the context was never initialized (or is shut down and torn
        down already), and :class:`RCLError` when a signal shut it down first (it is torn
        down all the same).
        """
        if not self._initialized:
            raise RuntimeError("Context must be initialized before it can be shutdown")
        interrupted = self._interrupted
        self._teardown()
        if interrupted:
            raise RCLError("failed to shutdown: rcl_shutdown already called on the given context")

    def try_shutdown(self) -> None:
        """Shut down if not shut down already; never an error."""
        if self._initialized:
            self._teardown()

    def _teardown(self) -> None:
        with self._lock:
            if not self._initialized:
                return
            self._initialized = False
            self._interrupted = False
            callbacks, self._shutdown_callbacks = self._shutdown_callbacks, []
            nodes = list(self._nodes)
        for node in nodes:
            node.wake()
        for callback in callbacks:
            callback()
        for node in nodes:
            node.close_entities()
        with self._lock:
            if self._graph is not None:
                self._graph.close()
                self._graph = None
            if self._router_watch is not None:
                with contextlib.suppress(Exception):  # its session may be closed already
                    self._router_watch.undeclare()
                self._router_watch = None
            if self._session is not None:
                close_session(self._session)
                self._session = None


_contexts: weakref.WeakSet[Context] = weakref.WeakSet()


def interrupt_all() -> None:
    """Shut every initialized context down as a signal does (see :meth:`Context.interrupt`)."""
    for context in list(_contexts):
        if context.ok():
            context.interrupt()


def _say(level: str, message: str) -> None:
    getattr(get_logger("launchkit.ros"), level)(message)


default_context = Context()
_refusals: list[ForeignRouterError] = []  # of every context of the process


def shutdown_all() -> None:
    """Shut the default context down and close every Zenoh session still open (what the
    process does at exit; ``launchkit._exit`` calls it before skipping the interpreter's
    teardown)."""
    for context in list(_contexts):
        context.try_shutdown()
    close_all()


def exit_status(status: int) -> int:
    """``status``, or 1 when a context of this process refused another user's router (a
    process that had to stop talking ends in failure, whatever its code made of it)."""
    return 1 if _refusals and status == 0 else status


def _at_exit() -> None:
    shutdown_all()
    if _refusals:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):
                stream.flush()
        os._exit(1)


# zenoh's callback threads are not daemons, and Python joins such threads *before* it runs
# atexit handlers: a session left open (an advanced subscriber especially) would hang the exit.
# threading's own exit hooks run before that join.
_register = getattr(threading, "_register_atexit", None)
if _register is not None:
    _register(_at_exit)
else:  # pragma: no cover - every supported Python has it
    atexit.register(_at_exit)
