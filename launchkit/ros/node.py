"""``Node``: the rclpy-like entry point for publishers, subscriptions, timers, services, params."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from launchkit.ros import names
from launchkit.ros.arguments import parse_ros_args
from launchkit.ros.clock import Clock, ClockType, ROSClock
from launchkit.ros.context import Context, default_context
from launchkit.ros.executor import Executor, WorkQueue
from launchkit.ros.keyexpr import node_token, topic_key
from launchkit.ros.logging import RcutilsLogger, apply_log_levels
from launchkit.ros.node_params import ParameterStore, SetParametersResult
from launchkit.ros.params import Parameter, overrides_for
from launchkit.ros.qos import QoSProfile, as_profile
from launchkit.ros.timer import Timer
from launchkit.ros.topics import Publisher, Subscription


class Node:
    """A ROS node: a name in a namespace, owning publishers, subscriptions, timers, services.

    ``--ros-args`` of the process (``-r __node:=``, ``-r __ns:=``, ``-r from:=to``, ``-p``,
    ``--params-file``, ``--log-level``) apply to it, as in rclpy.
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

    def _topic_key(self, fqn: str, type_name: str, type_hash: str) -> str:
        return topic_key(self.context.domain_id, fqn, type_name, type_hash)

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

    # parameters ---------------------------------------------------------------------------
    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare a parameter; a value from ``-p``/``--params-file``/``<param>`` wins."""
        return self._params.declare(name, value, descriptor, ignore_override)

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        """Declare several ``(name, default[, descriptor])`` under ``namespace.``."""
        prefix = f"{namespace}." if namespace else ""
        return [
            self.declare_parameter(
                prefix + entry[0],
                entry[1] if len(entry) > 1 else None,
                entry[2] if len(entry) > 2 else None,
                ignore_override,
            )
            for entry in parameters
        ]

    def has_parameter(self, name: str) -> bool:
        """Whether ``name`` is declared."""
        return name in self._params.params

    def get_parameter(self, name: str) -> Parameter:
        """The declared parameter ``name``."""
        return self._params.get(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter, or ``alternative_value`` when it is not declared."""
        if name in self._params.params:
            return self._params.params[name]
        return alternative_value or Parameter(name, Parameter.Type.NOT_SET, None)

    def get_parameters(self, names_: list[str]) -> list[Parameter]:
        """Several parameters."""
        return [self.get_parameter(n) for n in names_]

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under ``prefix.``, keyed by the rest of their name."""
        head = f"{prefix}." if prefix else ""
        return {n[len(head) :]: p for n, p in self._params.params.items() if n.startswith(head)}

    def set_parameters(self, parameter_list: list[Parameter]) -> list[SetParametersResult]:
        """Set parameters one by one (each may fail on its own)."""
        return self._params.set(parameter_list)

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> SetParametersResult:
        """Set all or none."""
        return self._params.set_atomically(parameter_list)

    def add_on_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], SetParametersResult]
    ) -> None:
        """Have ``callback`` approve or reject every parameter change."""
        self._params.on_set.append(callback)

    def remove_on_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], SetParametersResult]
    ) -> None:
        """Stop asking ``callback``."""
        self._params.on_set.remove(callback)

    @property
    def _parameters(self) -> dict[str, Parameter]:
        return self._params.params

    # entities -----------------------------------------------------------------------------
    def create_publisher(
        self, msg_type: Any, topic: str, qos_profile: QoSProfile | int, **_: Any
    ) -> Publisher:
        """A publisher of ``msg_type`` on ``topic`` (``qos_profile``: a profile or a depth)."""
        pub = Publisher(self, msg_type, topic, as_profile(qos_profile))
        self._entities.append(pub)
        return pub

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
        sub = Subscription(self, msg_type, topic, callback, as_profile(qos_profile), raw)
        self._entities.append(sub)
        return sub

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
        self, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any], **_: Any
    ) -> Any:
        """Serve ``srv_name``: ``callback(request, response)`` returns the response."""
        from launchkit.ros.services import Service

        service = Service(self, srv_type, srv_name, callback)
        self._entities.append(service)
        return service

    def create_client(self, srv_type: Any, srv_name: str, **_: Any) -> Any:
        """A client of ``srv_name`` (``call``, ``call_async``, ``wait_for_service``)."""
        from launchkit.ros.services import Client

        client = Client(self, srv_type, srv_name)
        self._entities.append(client)
        return client

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

    def _forget(self, entity: Any) -> None:
        if entity in self._entities:
            self._entities.remove(entity)

    # graph --------------------------------------------------------------------------------
    def count_publishers(self, topic_name: str) -> int:
        """Publishers on ``topic_name`` anywhere in the graph."""
        return len(self.context.graph.tokens("MP", self.resolve_topic_name(topic_name)))

    def count_subscribers(self, topic_name: str) -> int:
        """Subscriptions on ``topic_name`` anywhere in the graph."""
        return len(self.context.graph.tokens("MS", self.resolve_topic_name(topic_name)))

    def get_node_names(self) -> list[str]:
        """Names of the nodes in the graph."""
        return sorted({t.node_name for t in self.context.graph.tokens("NN")})

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        """(name, namespace) of the nodes in the graph."""
        return sorted({(t.node_name, t.namespace) for t in self.context.graph.tokens("NN")})

    def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
        """Every topic with its types."""
        topics: dict[str, set[str]] = {}
        for kind in ("MP", "MS"):
            for t in self.context.graph.tokens(kind):
                topics.setdefault(t.topic, set()).add(t.type_name)
        return sorted((name, sorted(types)) for name, types in topics.items())

    # executor plumbing -------------------------------------------------------------------
    @property
    def executor(self) -> Executor:
        """The executor running this node's callbacks."""
        return self._own_executor()

    def _own_executor(self) -> Executor:
        if self._executor is None:
            self._executor = Executor(context=self.context)
            self._executor.add_node(self)
        return self._executor

    def _wake(self) -> None:
        self._work.wake()

    def _close_entities(self) -> None:
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
        self._close_entities()
        self._wake()
