"""The launcher's ROS node: made on first use (joining the launch's router), spun on its own
thread; service calls run on worker threads, and what they report is posted to the launch's
loop."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from launchkit.description.ros_link import LoadRequest, Report
from launchkit.envvars import ROUTER
from launchkit.errors import LaunchkitError
from launchkit.ros.context import Context, NotInitializedError
from launchkit.ros.executor import ExternalShutdownException, SingleThreadedExecutor
from launchkit.ros.node import Node
from launchkit.ros.params import Parameter, load_params_file, parameter_from_value

LOAD_LOGGER = "launch_ros.actions.load_composable_nodes"
LIFECYCLE_LOGGER = "launch_ros.actions.lifecycle_node"
TRANSITION_NAMES = {
    1: "TRANSITION_CONFIGURE",
    2: "TRANSITION_CLEANUP",
    3: "TRANSITION_ACTIVATE",
    4: "TRANSITION_DEACTIVATE",
    5: "TRANSITION_UNCONFIGURED_SHUTDOWN",
    6: "TRANSITION_INACTIVE_SHUTDOWN",
    7: "TRANSITION_ACTIVE_SHUTDOWN",
}


class RosAdapter:
    """The :class:`~launchkit.description.ros_link.RosLink` of a running launch."""

    def __init__(
        self,
        environment: Callable[[], dict[str, str]],
        post: Callable[[Callable[[], None]], None],
    ) -> None:
        self._environment = environment  # where the router is (starting it if needed)
        self._post = post
        self._context: Context | None = None
        self._node: Node | None = None
        self._closed = threading.Event()
        self._threads: list[threading.Thread] = []

    # -- the node ------------------------------------------------------------------------------

    def _ensure(self) -> Node:
        if self._node is None:
            context = Context(router=self._environment().get(ROUTER))
            context.init([])
            self._context = context
            self._node = Node(
                f"launch_ros_{os.getpid()}", context=context, start_parameter_services=False
            )
            executor = SingleThreadedExecutor(context=context)
            executor.add_node(self._node)
            self._start(executor.spin)
        return self._node

    def _start(self, work: Callable[[], None]) -> None:
        def run() -> None:
            try:
                work()
            except (NotInitializedError, ExternalShutdownException):
                if not self._closed.is_set():
                    raise
                # the launch ended (a lifecycle node that exited at once, say) while this
                # worker waited for a service or spun: its context is gone, and so is its
                # purpose

        thread = threading.Thread(target=run, name="launchkit-ros-link", daemon=True)
        self._threads.append(thread)
        thread.start()

    def _report(self, report: Report, level: str, logger: str, message: str) -> None:
        self._post(lambda: report(level, logger, message))

    def _ready(self, client: Any, report: Report, logger: str) -> bool:
        """Wait for the client's service, giving up when the launch ends."""
        while not self._closed.is_set():
            if client.wait_for_service(timeout_sec=0.5):
                return True
        self._report(
            report,
            "WARNING",
            logger,
            f"Abandoning wait for the '{client.srv_name}' service, due to shutdown.",
        )
        return False

    def _call(self, client: Any, request: Any) -> Any:
        """The response, or None when the launch ends first."""
        future = client.call_async(request, timeout_sec=3600.0)
        while not future.wait(0.5):
            if self._closed.is_set():
                future.cancel()
                return None
        return future.result()

    # -- components ----------------------------------------------------------------------------

    def load_nodes(self, container: str, requests: list[LoadRequest], report: Report) -> None:
        """Load ``requests`` into ``container`` in order, on a worker thread."""
        from launchkit.ros.msgs.composition_interfaces.srv import LoadNode

        client = self._ensure().create_client(LoadNode, f"{container}/_container/load_node")

        def work() -> None:
            for request in requests:
                if not self._ready(client, report, LOAD_LOGGER):
                    return
                try:
                    response = self._call(client, _load_message(LoadNode, request))
                except Exception as error:  # the container died or answered garbage
                    message = f"Failed to load node of type '{request.plugin}': {error}"
                    self._report(report, "ERROR", LOAD_LOGGER, message)
                    continue
                if response is None:
                    return
                self._report(report, *_load_result(response, request, container))

        self._start(work)

    # -- lifecycle -----------------------------------------------------------------------------

    def watch_transitions(self, node: str, on_event: Callable[[Any], None]) -> None:
        """Post each of ``node``'s TransitionEvent messages to the launch's loop."""
        from launchkit.ros.msgs.lifecycle_msgs.msg import TransitionEvent

        def deliver(msg: Any) -> None:
            self._post(lambda: on_event(msg))

        self._ensure().create_subscription(TransitionEvent, f"{node}/transition_event", deliver, 10)

    def change_state(self, node: str, transition_id: int, report: Report) -> None:
        """Call ``node``'s ``~/change_state`` on a worker thread; report a failure."""
        from launchkit.ros.msgs.lifecycle_msgs.srv import ChangeState

        client = self._ensure().create_client(ChangeState, f"{node}/change_state")

        def work() -> None:
            if not self._ready(client, report, LIFECYCLE_LOGGER):
                return
            request = ChangeState.Request()
            request.transition.id = transition_id
            response = self._call(client, request)
            if response is not None and not response.success:
                name = TRANSITION_NAMES.get(transition_id, str(transition_id))
                message = f"Failed to make transition '{name}' for LifecycleNode '{node}'"
                self._report(report, "ERROR", LIFECYCLE_LOGGER, message)

        self._start(work)

    def close(self) -> None:
        """Stop the workers and leave the graph."""
        self._closed.set()
        if self._context is not None:
            self._context.try_shutdown()
        for thread in self._threads:
            thread.join(timeout=5)
        self._threads.clear()


def _parameters(request: LoadRequest) -> list[Parameter]:
    fqn = f"{request.namespace.rstrip('/')}/{request.node_name}" if request.node_name else ""
    values: dict[str, Any] = {}
    for item in request.parameters:
        if isinstance(item, Path):
            values.update(load_params_file(item, fqn or "/"))
        else:
            values[item[0]] = item[1]
    return [parameter_from_value(name, value) for name, value in values.items()]


def _load_message(srv: Any, request: LoadRequest) -> Any:
    from launchkit.ros.msgs.rcl_interfaces.msg import Parameter as ParameterMsg

    def messages(params: list[Parameter]) -> list[Any]:
        return [ParameterMsg(name=p.name, value=p.to_msg_value()) for p in params]

    try:
        parameters = _parameters(request)
        extra = [parameter_from_value(name, value) for name, value in request.extra_arguments]
    except LaunchkitError as error:
        raise RuntimeError(error.message) from None
    return srv.Request(
        package_name=request.package,
        plugin_name=request.plugin,
        node_name=request.node_name,
        node_namespace=request.namespace,
        remap_rules=list(request.remaps),
        parameters=messages(parameters),
        extra_arguments=messages(extra),
    )


def _load_result(response: Any, request: LoadRequest, container: str) -> tuple[str, str, str]:
    if response.success:
        message = f"Loaded node '{response.full_node_name}' in container '{container}'"
        return "INFO", LOAD_LOGGER, message
    name = response.full_node_name or request.node_name
    message = (
        f"Failed to load node '{name}' of type '{request.plugin}' in container "
        f"'{container}': {response.error_messsage}"
    )
    return "ERROR", LOAD_LOGGER, message
