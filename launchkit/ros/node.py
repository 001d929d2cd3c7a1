"""``Node``: the rclpy-like entry point for publishers, subscriptions, timers, services, params."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

from launchkit.ros import names
from launchkit.ros.arguments import parse_ros_args
from launchkit.ros.clock import Clock, ClockType, ROSClock
from launchkit.ros.context import Context, default_context
from launchkit.ros.executor import Executor, Work, WorkQueue
from launchkit.ros.keyexpr import node_token, topic_key
from launchkit.ros.logging import RcutilsLogger, apply_log_levels
from launchkit.ros.namesakes import NamesakeWatch
from launchkit.ros.node_graph import GraphQueries
from launchkit.ros.node_params import ParameterMethods, ParameterStore
from launchkit.ros.params import Parameter, overrides_for
from launchkit.ros.qos import QoSProfile, as_profile, qos_profile_services_default
from launchkit.ros.services import Client, Service
from launchkit.ros.timer import Timer
from launchkit.ros.topics import Publisher, Subscription

_E = TypeVar("_E")


class Node(ParameterMethods, GraphQueries):
    """A ROS node: a name in a namespace, owning publishers, subscriptions, timers, services.

    ``--ros-args`` of the process (``-r __node:=``, ``-r __ns:=``, ``-r from:=to``, ``-p``,
    ``--params-file``, ``--log-level``) apply to it, as in rclpy. Its publishers,
    subscriptions, services and clients use it through :class:`NodeInterface`, its executor
    through ``timers`` and ``route_work``.
    """

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        cli_args: list[str] | None = None,
        namespace: str | None = None,
        use_global_arguments: bool = True,
        start_parameter_services: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        enable_rosout: bool = True,
    ) -> None:
        self.context = context or default_context
        self.context.require()
        original = names.validate_node_name(node_name)
        rules = list(self.context.ros_args.remaps) if use_global_arguments else []
        local_args = parse_ros_args(cli_args or [])  # needs its own "--ros-args", as rclpy
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
        self._params = ParameterStore(overrides, allow_undeclared_parameters)

        self._work = WorkQueue()
        self._executor: Executor | None = None
        self._timers: list[Timer] = []
        self._entities: list[Any] = []
        self._clock = ROSClock()
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
        self._own(NamesakeWatch(session, self.context.domain_id, own, namespace, name, warn))

        self._params.post_set.append(self._on_params_set)
        self.declare_parameter("use_sim_time", False)
        if automatically_declare_parameters_from_overrides:
            for name, value in overrides.items():
                if name not in self._params.params:
                    self.declare_parameter(name, value)
        if start_parameter_services:
            from launchkit.ros.parameter_service import ParameterService

            self._parameter_service: Any = ParameterService(self)

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

    def _on_params_set(self, params: list[Parameter]) -> None:
        for param in params:
            if param.name == "use_sim_time":
                self._use_sim_time(bool(param.value))

    def _use_sim_time(self, enabled: bool) -> None:
        if enabled == self._clock.ros_time_is_active:
            return
        if enabled:
            from launchkit.ros.msgs import get_message
            from launchkit.ros.qos import ReliabilityPolicy

            clock_type = get_message("rosgraph_msgs/msg/Clock")
            self._clock._set_ros_time_override(True)
            self._clock_sub = self.create_subscription(
                clock_type,
                "/clock",
                lambda msg: self._clock._set_sim_time(
                    msg.clock.sec * 1_000_000_000 + msg.clock.nanosec
                ),
                QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT),
            )
        else:
            if self._clock_sub is not None:
                self.destroy_subscription(self._clock_sub)
                self._clock_sub = None
            self._clock._set_ros_time_override(False)

    # entities -----------------------------------------------------------------------------
    def create_publisher(
        self, msg_type: Any, topic: str, qos_profile: QoSProfile | int, **_: Any
    ) -> Publisher:
        """A publisher of ``msg_type`` on ``topic`` (``qos_profile``: a profile or a depth)."""
        return self._own(Publisher(self, msg_type, topic, as_profile(qos_profile)))

    def create_subscription(
        self,
        msg_type: Any,
        topic: str,
        callback: Callable[..., Any],
        qos_profile: QoSProfile | int,
        *,
        raw: bool = False,
        **_: Any,
    ) -> Subscription:
        """Call ``callback(msg)`` or ``callback(msg, info)`` for each message on ``topic``."""
        return self._own(
            Subscription(self, msg_type, topic, callback, as_profile(qos_profile), raw)
        )

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[[], Any] | None,
        clock: Clock | None = None,
        **_: Any,
    ) -> Timer:
        """Call ``callback`` every ``timer_period_sec`` of the node's clock."""
        timer = Timer(callback, timer_period_sec, clock or self._clock)
        self._timers.append(timer)
        self._work.wake()
        return timer

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Any:
        """A rate to ``sleep()`` at ``frequency`` Hz (in a thread other than the spinning one)."""
        from launchkit.ros.rate import Rate

        return Rate(frequency, clock or Clock(clock_type=ClockType.STEADY_TIME))

    def create_service(
        self,
        srv_type: Any,
        srv_name: str,
        callback: Callable[..., Any],
        *,
        qos_profile: QoSProfile | int = qos_profile_services_default,
        raw: bool = False,
        **_: Any,
    ) -> Any:
        """Serve ``srv_name``: ``callback(request, response)`` returns the response (raw: bytes)."""
        return self._own(Service(self, srv_type, srv_name, callback, as_profile(qos_profile), raw))

    def create_client(
        self,
        srv_type: Any,
        srv_name: str,
        *,
        qos_profile: QoSProfile | int = qos_profile_services_default,
        raw: bool = False,
        **_: Any,
    ) -> Any:
        """A client of ``srv_name`` (``call``, ``call_async``, ``wait_for_service``)."""
        return self._own(Client(self, srv_type, srv_name, as_profile(qos_profile), raw))

    def destroy_publisher(self, publisher: Publisher) -> bool:
        """Undeclare ``publisher``."""
        publisher.destroy()
        return True

    def destroy_subscription(self, subscription: Subscription) -> bool:
        """Undeclare ``subscription``."""
        subscription.destroy()
        return True

    def destroy_timer(self, timer: Timer) -> bool:
        """Stop and drop ``timer``."""
        timer.destroy()
        if timer in self._timers:
            self._timers.remove(timer)
        return True

    def destroy_service(self, service: Any) -> bool:
        """Undeclare ``service``."""
        service.destroy()
        return True

    def destroy_client(self, client: Any) -> bool:
        """Undeclare ``client``."""
        client.destroy()
        return True

    # the node interface (what its entities use; see node_interface.py) -------------------
    @property
    def zid(self) -> str:
        """The Zenoh session id the node's liveliness token carries."""
        return self._zid

    @property
    def node_id(self) -> int:
        """The node's id within its context."""
        return self._node_id

    def topic_key(self, fqn: str, type_name: str, type_hash: str) -> str:
        """The Zenoh key expression of a topic or service of this node's domain."""
        return topic_key(self.context.domain_id, fqn, type_name, type_hash)

    def post(self, work: Work) -> None:
        """Run ``work`` in the thread that spins the node (called from Zenoh's threads)."""
        self._work.put(work)

    def forget(self, entity: object) -> None:
        """``entity`` was destroyed: the node no longer closes it at shutdown."""
        if entity in self._entities:
            self._entities.remove(entity)

    def _own(self, entity: _E) -> _E:
        self._entities.append(entity)
        return entity

    # executor plumbing (what executors and the context use) --------------------------------
    @property
    def executor(self) -> Executor:
        """The executor running this node's callbacks (one of its own unless it was added to
        another)."""
        if self._executor is None:
            self._executor = Executor(context=self.context)
            self._executor.add_node(self)
        return self._executor

    @property
    def timers(self) -> list[Timer]:
        """The node's timers, for its executor."""
        return list(self._timers)

    def route_work(self, queue: WorkQueue | None) -> WorkQueue:
        """Send the node's callbacks to ``queue`` from now on (None: a queue of its own, when
        it leaves an executor); the previous queue, whose pending work the caller moves."""
        previous, self._work = self._work, queue or WorkQueue()
        return previous

    def wake(self) -> None:
        """Make a blocked spin of this node look again (shutdown, a new timer)."""
        self._work.wake()

    def close_entities(self) -> None:
        """Undeclare every entity and the node's token (the context is shutting down)."""
        for entity in list(self._entities):
            entity.destroy()
        for timer in self._timers:
            timer.destroy()
        if self._token is not None:
            try:
                self._token.undeclare()
            except Exception:  # the session may be closed already
                pass
            self._token = None

    def destroy_node(self) -> None:
        """Undeclare everything the node owns (its executor stops running it)."""
        if self._destroyed:
            return
        self._destroyed = True
        self.close_entities()
        self.wake()
