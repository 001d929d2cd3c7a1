"""``Node``: rclpy's entry point for publishers, subscriptions, timers, services, parameters.

Every node, as in rclpy, publishes ``/parameter_events`` and (unless ``enable_rosout=False``)
``/rosout``, serves its parameters (``start_parameter_services``) and, with
``enable_logger_service=True``, its logger levels. Its callbacks belong to callback groups (the
node's default group is mutually exclusive) and run in the executor it is added to.
"""

from __future__ import annotations

import weakref
from collections.abc import Iterator
from typing import Any, TypeVar

from launchkit.ros import names
from launchkit.ros.arguments import parse_ros_args
from launchkit.ros.callback_groups import (
    CallbackGroup,
    MutuallyExclusiveCallbackGroup,
    ReentrantCallbackGroup,
)
from launchkit.ros.clock import Clock, ROSClock, Time
from launchkit.ros.context import Context, NotInitializedException, default_context
from launchkit.ros.executor import Executor
from launchkit.ros.guard_condition import GuardCondition
from launchkit.ros.keyexpr import node_token, topic_key
from launchkit.ros.logging import RcutilsLogger, apply_log_levels
from launchkit.ros.namesakes import NamesakeWatch
from launchkit.ros.node_entities import EntityMethods
from launchkit.ros.node_graph import GraphQueries
from launchkit.ros.node_params import ParameterMethods
from launchkit.ros.parameter_store import ParameterStore, descriptor_message
from launchkit.ros.params import Parameter, overrides_for
from launchkit.ros.qos import QoSProfile, ReliabilityPolicy, qos_profile_parameter_events
from launchkit.ros.task import NodeTasks
from launchkit.ros.timer import Timer
from launchkit.ros.topics import Publisher, Subscription
from launchkit.ros.work_queue import WorkQueue

_E = TypeVar("_E")
USE_SIM_TIME = "use_sim_time"


class Node(EntityMethods, ParameterMethods, GraphQueries):
    """A ROS node: a name in a namespace, owning publishers, subscriptions, timers, services.

    ``--ros-args`` of the process (``-r __node:=``, ``-r __ns:=``, ``-r from:=to``, ``-p``,
    ``--params-file``, ``--log-level``) apply to it, as in rclpy. Its entities use it through
    :class:`~launchkit.ros.node_interface.NodeInterface`, executors through ``work``,
    ``timers`` and ``executor``.
    """

    PARAM_REL_TOL = 1e-6

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        cli_args: list[str] | None = None,
        namespace: str | None = None,
        use_global_arguments: bool = True,
        enable_rosout: bool = True,
        start_parameter_services: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        enable_logger_service: bool = False,
    ) -> None:
        self.context = context or default_context
        if not self.context.ok():
            raise NotInitializedException("cannot create node")
        original = names.validate_node_name(node_name)
        rules = list(self.context.ros_args.remaps) if use_global_arguments else []
        local_args = parse_ros_args(["--ros-args", *(cli_args or [])])
        rules = local_args.remaps + rules
        self._remaps = rules
        self._original_name = original
        self._name = names.remap_node_name(rules, original)
        self._namespace = names.remap_namespace(
            rules, original, names.normalize_namespace(namespace or "")
        )
        self._logger = RcutilsLogger(self._logger_name())
        apply_log_levels(self.context.ros_args.log_levels)
        apply_log_levels(local_args.log_levels)

        fqn = self.get_fully_qualified_name()
        overrides: dict[str, Any] = {}
        if use_global_arguments:
            overrides.update(overrides_for(self.context.ros_args, original, fqn))
        overrides.update(overrides_for(local_args, original, fqn))
        for param in parameter_overrides or []:
            overrides[param.name] = param.value
        self._params = ParameterStore(overrides, allow_undeclared_parameters, self._on_params)

        self._work = WorkQueue()
        self._scheduler = NodeTasks(self._work.put)
        self._executor_ref: weakref.ref[Executor] | None = None
        self._publishers: list[Publisher] = []
        self._subscriptions: list[Subscription] = []
        self._clients: list[Any] = []
        self._services: list[Any] = []
        self._timers: list[Timer] = []
        self._guards: list[GuardCondition] = []
        self._waitables: list[Any] = []
        self._default_callback_group = MutuallyExclusiveCallbackGroup()
        self._rate_group = ReentrantCallbackGroup()
        self._clock = ROSClock()
        self._clock.sleep_watcher = self.context.lockstep
        self._clock_sub: Subscription | None = None
        self._destroyed = False

        session = self.context.session
        self._zid = str(session.zid())
        self._node_id = self.context.next_entity_id()
        self._token: Any = session.liveliness().declare_token(
            node_token(
                self.context.domain_id,
                self._zid,
                self._node_id,
                self.context.ros_args.enclave,
                self._namespace,
                self._name,
            )
        )
        self.context.add_node(self)
        own = (self._zid, str(self._node_id))
        namespace, name, warn = self._namespace, self._name, self._logger.warning
        self._namesakes: NamesakeWatch | None = NamesakeWatch(
            session, self.context.domain_id, own, namespace, name, warn
        )

        from launchkit.ros.msgs import get_message

        self._parameter_event_publisher: Publisher | None = self.create_publisher(
            get_message("rcl_interfaces/msg/ParameterEvent"),
            "/parameter_events",
            qos_profile_parameter_events,
        )
        self._rosout: Any = None
        if enable_rosout and self.context.ros_args.rosout_logs:
            from launchkit.ros.rosout import Rosout

            self._rosout = Rosout(self.create_publisher, self._logger.name)
        if automatically_declare_parameters_from_overrides:
            self.declare_parameters(
                "",
                [(name, value, descriptor_message()) for name, value in overrides.items()],
                ignore_override=True,
            )
        if not self.has_parameter(USE_SIM_TIME):
            # in a lockstep launch every node runs on the launch's simulated clock
            self.declare_parameter(USE_SIM_TIME, self.context.lockstep is not None)
        self._use_sim_time(self.get_parameter(USE_SIM_TIME).value is True)
        self._params.post_set.append(self._on_params_set)
        if start_parameter_services:
            from launchkit.ros.parameter_service import ParameterService

            self._parameter_service = ParameterService(self)
        if enable_logger_service:
            from launchkit.ros.logger_service import LoggerService

            self._logger_service = LoggerService(self.create_service, self._name)

    # names ------------------------------------------------------------------------------
    def get_name(self) -> str:
        """The node's name (after ``__node:=`` remapping)."""
        return self._name

    def get_namespace(self) -> str:
        """The node's namespace (``/`` at the root)."""
        return self._namespace

    def get_fully_qualified_name(self) -> str:
        """``/namespace/name``."""
        return names.node_fqn(self._name, self._namespace)

    def _logger_name(self) -> str:
        ns = self._namespace.strip("/").replace("/", ".")
        return f"{ns}.{self._name}" if ns else self._name

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """Expand ``topic`` for this node and apply remapping rules."""
        expanded = names.expand(topic, self._name, self._namespace, "topic")
        if only_expand:
            return expanded
        return names.remap_name(
            self._remaps, expanded, self._original_name, self._name, self._namespace
        )

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        """Expand ``service`` for this node and apply remapping rules."""
        expanded = names.expand(service, self._name, self._namespace, "service")
        if only_expand:
            return expanded
        return names.remap_name(
            self._remaps, expanded, self._original_name, self._name, self._namespace, "service"
        )

    # logging and time ---------------------------------------------------------------------
    def get_logger(self) -> RcutilsLogger:
        """The node's logger (named after the node)."""
        return self._logger

    def get_clock(self) -> Clock:
        """The node's ROS clock (follows ``/clock`` when ``use_sim_time`` is true)."""
        return self._clock

    def _on_params(self, new: list[Any], changed: list[Any], deleted: list[Any]) -> None:
        """Publish a successful declare or set on ``/parameter_events``."""
        publisher = getattr(self, "_parameter_event_publisher", None)
        if publisher is None:
            return
        from launchkit.ros.msgs import get_message

        event = get_message("rcl_interfaces/msg/ParameterEvent")(
            stamp=self._clock.now().to_msg(),
            node=self.get_fully_qualified_name(),
            new_parameters=new,
            changed_parameters=changed,
            deleted_parameters=deleted,
        )
        publisher.publish(event)

    def _on_params_set(self, params: list[Parameter]) -> None:
        for param in params:
            if param.name == USE_SIM_TIME:
                if param.value is not True and param.value is not False:
                    self._logger.error(
                        f"Invalid type for parameter '{USE_SIM_TIME}' {param.type_!r} "
                        "should be bool"
                    )
                    continue
                self._use_sim_time(param.value)

    def _use_sim_time(self, enabled: bool) -> None:
        if enabled == self._clock.ros_time_is_active:
            return
        if enabled:
            from launchkit.ros.msgs import get_message

            clock_type = get_message("rosgraph_msgs/msg/Clock")
            self._clock._set_ros_time_is_active(True)
            self._clock_sub = self.create_subscription(
                clock_type,
                "/clock",
                lambda msg: self._clock.set_ros_time_override(Time.from_msg(msg.clock)),
                QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT),
            )
        else:
            if self._clock_sub is not None:
                self.destroy_subscription(self._clock_sub)
                self._clock_sub = None
            self._clock._set_ros_time_is_active(False)

    # the node interface (what its entities use; see node_interface.py) -------------------
    @property
    def zid(self) -> str:
        """The Zenoh session id the node's liveliness token carries."""
        return self._zid

    @property
    def node_id(self) -> int:
        """The node's id within its context."""
        return self._node_id

    @property
    def scheduler(self) -> NodeTasks:
        """Where the done callbacks of the node's futures are scheduled (its work queue)."""
        return self._scheduler

    def topic_key(self, fqn: str, type_name: str, type_hash: str) -> str:
        """The Zenoh key expression of a topic or service of this node's domain."""
        return topic_key(self.context.domain_id, fqn, type_name, type_hash)

    def post(self, work: Any) -> None:
        """Queue a ready entity or a task for the executor (called from Zenoh's threads)."""
        self._work.put(work)

    def forget(self, entity: object) -> None:
        """``entity`` was destroyed: the node no longer holds it."""
        for entities in (self._publishers, self._subscriptions, self._clients, self._services):
            if entity in entities:
                entities.remove(entity)  # type: ignore[arg-type]

    # executor plumbing (what executors and the context use) --------------------------------
    @property
    def default_callback_group(self) -> CallbackGroup:
        """The group of the entities made without one (mutually exclusive)."""
        return self._default_callback_group

    @property
    def executor(self) -> Executor | None:
        """The executor the node was added to, if any."""
        return None if self._executor_ref is None else self._executor_ref()

    @executor.setter
    def executor(self, new_executor: Executor | None) -> None:
        current = self.executor
        if current is new_executor:
            return
        if current is not None:
            current.remove_node(self)
        if new_executor is None:
            self._executor_ref = None
        else:
            new_executor.add_node(self)
            self._executor_ref = weakref.ref(new_executor)

    @property
    def work(self) -> WorkQueue:
        """The node's queue of ready entities and tasks."""
        return self._work

    @property
    def publishers(self) -> Iterator[Publisher]:
        """The node's publishers."""
        yield from self._publishers

    @property
    def subscriptions(self) -> Iterator[Subscription]:
        """The node's subscriptions."""
        yield from self._subscriptions

    @property
    def clients(self) -> Iterator[Any]:
        """The node's service clients."""
        yield from self._clients

    @property
    def services(self) -> Iterator[Any]:
        """The node's services."""
        yield from self._services

    @property
    def timers(self) -> list[Timer]:
        """The node's timers."""
        return list(self._timers)

    @property
    def guards(self) -> Iterator[GuardCondition]:
        """The node's guard conditions."""
        yield from self._guards

    @property
    def waitables(self) -> Iterator[Any]:
        """The waitables added to the node (action servers and clients)."""
        yield from self._waitables

    def _wake_executor(self) -> None:
        executor = self.executor
        if executor is not None:
            executor.wake()

    def wake(self) -> None:
        """Make a blocked spin of this node look again (shutdown, a new timer)."""
        self._work.wake()

    def close_entities(self) -> None:
        """Undeclare every entity and the node's token (the context is shutting down)."""
        if self._rosout is not None:
            self._rosout.destroy()
            self._rosout = None
        self._parameter_event_publisher = None
        if self._namesakes is not None:
            self._namesakes.destroy()
            self._namesakes = None
        for entity in [*self._publishers, *self._subscriptions, *self._clients, *self._services]:
            entity.destroy()
        for timer in self._timers:
            timer.destroy()
        self._publishers.clear()
        self._subscriptions.clear()
        self._clients.clear()
        self._services.clear()
        self._timers.clear()
        self._guards.clear()
        if self._token is not None:
            try:
                self._token.undeclare()
            except Exception:  # the session may be closed already
                pass
            self._token = None

    def destroy_node(self) -> None:
        """Destroy everything the node owns (its executor stops running it)."""
        if self._destroyed:
            return
        self._destroyed = True
        self.close_entities()
        self._wake_executor()
        self.wake()
