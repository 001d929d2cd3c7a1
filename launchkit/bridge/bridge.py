"""The bridge: one launchkit node and one rclpy node in one process, kept in step with both
graphs. ``reconcile()`` compares what should be bridged (:func:`launchkit.bridge.plan.plan`) with
what is, and opens, re-opens, (de)activates or closes routes to match."""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass, field
from typing import Any

from launchkit.bridge._rclpy import import_rclpy
from launchkit.bridge.echo_guard import EchoGuard
from launchkit.bridge.graph_view import dds_view, zenoh_view
from launchkit.bridge.plan import DDS, ZENOH, NameFilter, ServiceRoute, TopicRoute, plan
from launchkit.bridge.service_route import ServiceBridge
from launchkit.bridge.topic_route import MissingTypeError, TopicBridge
from launchkit.errors import RuntimeLaunchError, UserError
from launchkit.ros.context import Context
from launchkit.ros.executors import SingleThreadedExecutor as ZenohExecutor
from launchkit.ros.node import Node
from launchkit.ros.qos import QoSProfile

NODE_NAME = "launchkit_bridge"


class BridgeUsageError(UserError):
    """The bridge cannot run in this environment as asked."""


@dataclass
class BridgeOptions:
    """What ``launchkit bridge`` was asked: filters, services on or off, discovery period."""

    names: NameFilter = field(default_factory=NameFilter)
    services: bool = True
    poll_period: float = 0.1  # seconds between two looks at the DDS graph
    router: str | None = None
    ros_argv: list[str] = field(default_factory=list)  # ["prog", "--ros-args", ...]


def describe(qos: QoSProfile) -> str:
    """``reliable transient_local depth 1`` (for the log)."""
    return (
        f"{qos.reliability.name.lower()} {qos.durability.name.lower()} depth {qos.effective_depth}"
    )


class Bridge:
    """Both nodes, their spinning threads, and the routes between them."""

    def __init__(self, options: BridgeOptions) -> None:
        self.options = options
        if os.environ.get("RMW_IMPLEMENTATION") == "rmw_zenoh_cpp":
            raise BridgeUsageError(
                "RMW_IMPLEMENTATION=rmw_zenoh_cpp: the bridge joins a DDS graph, and rmw_zenoh "
                "nodes reach launchkit's router without it (docs/ros2-interop.md)",
                expected="RMW_IMPLEMENTATION unset or a DDS one for the bridge",
            )
        rclpy = import_rclpy()
        from rclpy.callback_groups import ReentrantCallbackGroup
        from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions

        self._zenoh_context = Context(router=options.router)
        self._zenoh_context.init(options.ros_argv)
        self.zenoh_node = Node(
            NODE_NAME, context=self._zenoh_context, start_parameter_services=False
        )
        self.log = self.zenoh_node.get_logger()
        self._dds_context = rclpy.Context()
        try:
            rclpy.init(
                args=options.ros_argv,
                context=self._dds_context,
                signal_handler_options=SignalHandlerOptions.NO,
            )
        except Exception as exc:  # rcl's errors (a wrong RMW_IMPLEMENTATION, say): one line
            self._zenoh_context.try_shutdown()
            message = " ".join(str(exc).split())
            raise RuntimeLaunchError(f"rclpy cannot start: {message}") from None
        # two rclpy nodes: topics on a single-threaded executor (rclpy's multi-threaded one
        # costs ~2 ms a callback here), services on a multi-threaded one, where a forwarded
        # call may block its thread for as long as the server takes
        self.dds_node, self.dds_services_node = (
            rclpy.create_node(
                name,
                context=self._dds_context,
                start_parameter_services=False,
                enable_rosout=False,
            )
            for name in (NODE_NAME, NODE_NAME + "_services")
        )
        self._services_group = ReentrantCallbackGroup()
        self._dds_executor = SingleThreadedExecutor(context=self._dds_context)
        self._dds_executor.add_node(self.dds_node)
        self._dds_services_executor = MultiThreadedExecutor(
            num_threads=4, context=self._dds_context
        )
        self._dds_services_executor.add_node(self.dds_services_node)
        self._zenoh_executor = ZenohExecutor(context=self._zenoh_context)
        self._zenoh_executor.add_node(self.zenoh_node)
        self._guard = EchoGuard()
        self._topics: dict[tuple[str, str], TopicBridge] = {}
        self._services: dict[tuple[str, str], ServiceBridge] = {}
        self._missing: set[tuple[str, str]] = set()  # (name, type) one side has no type for
        self._warned: set[str] = set()  # each reason is logged once
        self.changed = threading.Event()
        self._stop = threading.Event()
        self._threads = [
            threading.Thread(
                target=self._spin_dds, args=(self._dds_executor,), name="bridge-dds", daemon=True
            ),
            threading.Thread(
                target=self._spin_dds,
                args=(self._dds_services_executor,),
                name="bridge-dds-services",
                daemon=True,
            ),
            threading.Thread(target=self._spin_zenoh, name="bridge-zenoh", daemon=True),
        ]
        for thread in self._threads:
            thread.start()
        self._zenoh_context.graph.add_listener(lambda token, appeared: self.changed.set())

    # spinning ----------------------------------------------------------------------------------
    def _spin_dds(self, executor: Any) -> None:
        while not self._stop.is_set():
            try:
                executor.spin_once(timeout_sec=0.1)
            except Exception as exc:  # a route closed under a callback: log, go on
                if not self._stop.is_set():
                    self.log.error(f"DDS side: {exc}", throttle_duration_sec=5.0)

    def _spin_zenoh(self) -> None:
        while not self._stop.is_set():
            try:
                self._zenoh_executor.spin_once(timeout_sec=0.1)
            except Exception as exc:
                if not self._stop.is_set():
                    self.log.error(f"launchkit side: {exc}", throttle_duration_sec=5.0)

    # keeping the routes in step ----------------------------------------------------------------
    def run(self, stop: threading.Event) -> None:
        """Reconcile on every launchkit graph change and every ``poll_period`` until ``stop``."""
        rmw = self._rmw_name()
        self.log.info(
            f"bridging ROS_DOMAIN_ID {self._zenoh_context.domain_id} between launchkit and {rmw}"
        )
        while not stop.is_set():
            self.changed.clear()
            self.reconcile()
            self.changed.wait(self.options.poll_period)

    def _rmw_name(self) -> str:
        from rclpy.utilities import get_rmw_implementation_identifier

        return str(get_rmw_implementation_identifier())

    def reconcile(self) -> None:
        """Open, adjust and close routes to match both graphs now."""
        wanted = plan(
            zenoh_view(
                self._zenoh_context.graph.tokens(), str(self.zenoh_node.context.session.zid())
            ),
            dds_view(self.dds_node, [self.dds_node, self.dds_services_node]),
            self.options.names,
            self.options.services,
        )
        for name, reason in wanted.skipped.items():
            self._refuse(name, reason)
        for key in [k for k in self._topics if k not in wanted.topics]:
            self._close_topic(key)
        for route in wanted.topics.values():
            self._want_topic(route)
        for key in [k for k in self._services if k not in wanted.services]:
            self._close_service(key)
        for service in wanted.services.values():
            self._want_service(service)

    def _want_topic(self, route: TopicRoute) -> None:
        current = self._topics.get(route.key)
        if current is not None and (current.route.type_name, current.route.qos) != (
            route.type_name,
            route.qos,
        ):
            self._close_topic(route.key)
            current = None
        if current is None:
            if (route.topic, route.type_name) in self._missing:
                return
            try:
                current = TopicBridge(
                    route, self.zenoh_node, self.dds_node, self._guard, self._topic_group()
                )
            except MissingTypeError as exc:
                self._missing.add((route.topic, route.type_name))
                self._refuse(route.topic, str(exc))
                return
            self._topics[route.key] = current
            self.log.info(
                f"bridging {route.topic} ({route.type_name}) {route.source} -> "
                f"{_other(route.source)}, {describe(route.qos)}"
            )
        current.route = route
        if route.active:
            current.activate()
        else:
            current.deactivate()

    def _topic_group(self) -> Any:
        # one mutually exclusive group per topic: messages of a topic stay in order, topics
        # do not wait for each other
        from rclpy.callback_groups import MutuallyExclusiveCallbackGroup

        return MutuallyExclusiveCallbackGroup()  # type: ignore[no-untyped-call]

    def _want_service(self, route: ServiceRoute) -> None:
        current = self._services.get(route.key)
        if current is not None and current.route.type_name != route.type_name:
            self._close_service(route.key)
            current = None
        if current is None:
            if (route.service, route.type_name) in self._missing:
                return
            try:
                current = ServiceBridge(
                    route, self.zenoh_node, self.dds_services_node, self._services_group
                )
            except MissingTypeError as exc:
                self._missing.add((route.service, route.type_name))
                self._refuse(route.service, str(exc))
                return
            self._services[route.key] = current
            self.log.info(
                f"bridging service {route.service} ({route.type_name}): {_other(route.source)} "
                f"clients -> {route.source} server"
            )
        current.poll()

    def _refuse(self, name: str, reason: str) -> None:
        if reason not in self._warned:  # a missing type: one line, not one per node
            self._warned.add(reason)
            self.log.warn(f"not bridging {name} (nor others for the same reason): {reason}")

    def _close_topic(self, key: tuple[str, str]) -> None:
        bridge = self._topics.pop(key)
        bridge.close()
        self.log.info(f"stopped bridging {bridge.route.topic} {key[0]} -> {_other(key[0])}")

    def _close_service(self, key: tuple[str, str]) -> None:
        bridge = self._services.pop(key)
        bridge.close()
        self.log.info(f"stopped bridging service {bridge.route.service}")

    def close(self) -> None:
        """Close every route, stop both spinners, shut both contexts down."""
        for key in list(self._topics):
            self._topics.pop(key).close()
        for key in list(self._services):
            self._services.pop(key).close()
        self._stop.set()
        for thread in self._threads:
            thread.join(timeout=5)
        for executor in (self._dds_executor, self._dds_services_executor):
            executor.shutdown(timeout_sec=1.0)
        self.dds_node.destroy_node()
        self.dds_services_node.destroy_node()
        self._dds_context.try_shutdown()
        self._zenoh_context.try_shutdown()


def _other(side: str) -> str:
    return DDS if side == ZENOH else ZENOH
