"""The ROS network a launch hosts: a Zenoh router started with the first ``<node>``."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from launchkit.envvars import LOCKSTEP as LOCKSTEP_ENV
from launchkit.envvars import ROUTER as ROUTER_ENV
from launchkit.envvars import ROUTER_AUTOSTART as AUTOSTART_ENV

if TYPE_CHECKING:
    from launchkit.description.launch_context import Runner
    from launchkit.ros.federation import RouterOptions as RouterOptions  # for api's type


class RouterHandle(Protocol):
    """What ``launchkit.ros.router.start_router`` returns."""

    endpoint: str
    hosted: bool
    shared: bool
    warnings: list[str]

    def close(self) -> None:
        """Stop the router (when this process hosts it)."""


class NodeNetwork:
    """Starts the router once, when the first node starts, and tells nodes where it is.

    The launch owns its network: it hosts the router for as long as it runs, or joins one of
    this user's already listening at the endpoint (the shared background router, say), and its
    processes never start a router of their own (``LAUNCHKIT_ROUTER_AUTOSTART=0``): a ROS
    program started before the first node waits for the launch's router.
    """

    def __init__(self, endpoint: str | None = None, options: RouterOptions | None = None) -> None:
        self.endpoint = endpoint
        self.options = options  # None: the LAUNCHKIT_ROUTER_* variables say
        self._router: RouterHandle | None = None
        #: Every process of the launch takes part in its lockstep clock (``--lockstep``).
        self.lockstep = False

    def ensure(self, runner: Runner) -> dict[str, str]:
        """Environment additions for a node process (starting the router if needed)."""
        if self._router is None:

            def report(level: str, message: str) -> None:  # called from the router's thread
                runner.log("WARNING" if level == "warn" else "INFO", "launch", message)

            self._router = router = _start_router(self.endpoint, self.options, report)
            verb = "started" if router.hosted else "joined"
            shared = " shared" if router.shared else ""
            runner.log("INFO", "launch", f"{verb} the{shared} ROS router at {router.endpoint}")
            for warning in router.warnings:
                runner.log("WARNING", "launch", warning)
            if not router.hosted and self.options is not None and not self.options.empty:
                runner.log(
                    "WARNING",
                    "launch",
                    f"the router at {router.endpoint} was already running: this launch's "
                    "--listen/--connect/--tls settings apply only to a router it starts",
                )
        return {ROUTER_ENV: self._router.endpoint, AUTOSTART_ENV: "0", **self._lockstep_env()}

    def known(self) -> dict[str, str]:
        """Environment additions for any other process: where the router is or will be, when
        the launch knows (``--router``, or a router already started), without starting one.

        A plain ``<executable>`` may still be a ROS program (gazebo_ros's ``gzserver`` is an
        ``ExecuteProcess``); in ROS it finds the others through DDS, here it needs the address.
        """
        environment = {AUTOSTART_ENV: "0", **self._lockstep_env()}
        if self._router is not None:
            environment[ROUTER_ENV] = self._router.endpoint
        elif self.endpoint:
            environment[ROUTER_ENV] = self.endpoint
        return environment

    def _lockstep_env(self) -> dict[str, str]:
        return {LOCKSTEP_ENV: "1"} if self.lockstep else {}

    def close(self) -> None:
        """Stop the router if this launch hosts it."""
        if self._router is not None:
            self._router.close()
            self._router = None


def _start_router(
    endpoint: str | None, options: RouterOptions | None, report: Callable[[str, str], None]
) -> Any:
    # zenoh is heavy: imported only when the first node starts
    from launchkit.ros.router import start_router

    return start_router(endpoint, options=options, report=report)


# ROUTER_ENV stays importable from here for launchkit.testing (its name is in launchkit.envvars).
__all__ = ["ROUTER_ENV", "NodeNetwork", "RouterHandle"]
