"""The ``create_*`` and ``destroy_*`` methods of :class:`launchkit.ros.Node` (rclpy's)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from launchkit.ros.callback_groups import CallbackGroup
from launchkit.ros.guard_condition import GuardCondition
from launchkit.ros.qos import QoSProfile, as_profile, qos_profile_services_default
from launchkit.ros.services import Client, Service
from launchkit.ros.timer import Timer
from launchkit.ros.topics import Publisher, Subscription

if TYPE_CHECKING:
    from launchkit.ros.clock import Clock, ROSClock
    from launchkit.ros.context import Context
    from launchkit.ros.rate import Rate
    from launchkit.ros.work_queue import WorkQueue


class EntityMethods:
    """Making and destroying a node's entities; mixed into ``Node``."""

    context: Context
    _publishers: list[Publisher]
    _subscriptions: list[Subscription]
    _clients: list[Any]
    _services: list[Any]
    _timers: list[Timer]
    _guards: list[GuardCondition]
    _waitables: list[Any]
    _clock: ROSClock
    _rate_group: CallbackGroup
    _work: WorkQueue

    @property
    def default_callback_group(self) -> CallbackGroup:
        """The group of entities made without one (``Node`` defines it)."""
        raise NotImplementedError

    def _wake_executor(self) -> None:
        raise NotImplementedError

    def _group(self, entity: Any, group: CallbackGroup | None) -> None:
        entity.callback_group = group or self.default_callback_group
        entity.callback_group.add_entity(entity)

    def create_publisher(
        self,
        msg_type: Any,
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: Any = None,
        qos_overriding_options: Any = None,
        publisher_class: type[Publisher] = Publisher,
    ) -> Publisher:
        """A publisher of ``msg_type`` on ``topic`` (``qos_profile``: a profile or a depth)."""
        publisher = publisher_class(
            self,  # type: ignore[arg-type]
            msg_type,
            topic,
            as_profile(qos_profile),
            callback_group,
        )
        publisher._set_event_callbacks(event_callbacks)
        self._publishers.append(publisher)
        self._wake_executor()
        return publisher

    def create_subscription(
        self,
        msg_type: Any,
        topic: str,
        callback: Callable[..., Any],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: Any = None,
        qos_overriding_options: Any = None,
        raw: bool = False,
    ) -> Subscription:
        """Call ``callback(msg)`` or ``callback(msg, info)`` for each message on ``topic``
        (``raw=True``: the message's serialized bytes)."""
        subscription = Subscription(
            self,  # type: ignore[arg-type]
            msg_type,
            topic,
            callback,
            as_profile(qos_profile),
            raw,
            callback_group,
        )
        subscription._set_event_callbacks(event_callbacks)
        self._subscriptions.append(subscription)
        self._wake_executor()
        return subscription

    def create_client(
        self,
        srv_type: Any,
        srv_name: str,
        *,
        qos_profile: QoSProfile | int = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        raw: bool = False,
    ) -> Client:
        """A client of ``srv_name`` (``call``, ``call_async``, ``wait_for_service``)."""
        client = Client(
            self,  # type: ignore[arg-type]
            srv_type,
            srv_name,
            as_profile(qos_profile),
            raw,
            callback_group,
        )
        self._clients.append(client)
        self._wake_executor()
        return client

    def create_service(
        self,
        srv_type: Any,
        srv_name: str,
        callback: Callable[..., Any],
        *,
        qos_profile: QoSProfile | int = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        raw: bool = False,
        service_class: type[Service] = Service,
    ) -> Service:
        """Serve ``srv_name``: ``callback(request, response)`` returns the response
        (``raw=True``: bytes in, bytes or a Future of them out; ``service_class``: a subclass
        that answers differently, as an action server's services do)."""
        service = service_class(
            self,  # type: ignore[arg-type]
            srv_type,
            srv_name,
            callback,
            as_profile(qos_profile),
            raw,
            callback_group,
        )
        self._services.append(service)
        self._wake_executor()
        return service

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[[], Any] | None,
        callback_group: CallbackGroup | None = None,
        clock: Clock | None = None,
        autostart: bool = True,
    ) -> Timer:
        """Call ``callback`` every ``timer_period_sec`` of the node's clock (or ``clock``)."""
        timer = Timer(callback, timer_period_sec, clock or self._clock, autostart=autostart)
        self._group(timer, callback_group)
        self._timers.append(timer)
        self._wake_executor()
        self._work.wake()
        return timer

    def create_guard_condition(
        self, callback: Callable[[], Any], callback_group: CallbackGroup | None = None
    ) -> GuardCondition:
        """A guard condition: ``trigger()`` has the executor call ``callback``."""
        guard = GuardCondition(callback, None, context=self.context)
        self._group(guard, callback_group)
        guard._attach(self._work.put)
        self._guards.append(guard)
        self._wake_executor()
        return guard

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Rate:
        """A rate to ``sleep()`` at ``frequency`` Hz of the node's clock."""
        from launchkit.ros.rate import Rate

        if frequency <= 0:
            raise ValueError("frequency must be > 0")
        return Rate(frequency, clock or self._clock, context=self.context)

    def add_waitable(self, waitable: Any) -> None:
        """Run ``waitable`` (an entity with ``_take_for_executor``) in the node's executor."""
        self._waitables.append(waitable)
        self._wake_executor()

    def remove_waitable(self, waitable: Any) -> None:
        """Stop running ``waitable``."""
        self._waitables.remove(waitable)
        self._wake_executor()

    def destroy_publisher(self, publisher: Publisher) -> bool:
        """Undeclare ``publisher``; False if it is not this node's."""
        if publisher not in self._publishers:
            return False
        publisher.destroy()
        return True

    def destroy_subscription(self, subscription: Subscription) -> bool:
        """Undeclare ``subscription``; False if it is not this node's."""
        if subscription not in self._subscriptions:
            return False
        subscription.destroy()
        return True

    def destroy_client(self, client: Any) -> bool:
        """Undeclare ``client``; False if it is not this node's."""
        if client not in self._clients:
            return False
        client.destroy()
        return True

    def destroy_service(self, service: Any) -> bool:
        """Undeclare ``service``; False if it is not this node's."""
        if service not in self._services:
            return False
        service.destroy()
        return True

    def destroy_timer(self, timer: Timer) -> bool:
        """Stop and drop ``timer``; False if it is not this node's."""
        if timer not in self._timers:
            return False
        timer.destroy()
        self._timers.remove(timer)
        return True

    def destroy_guard_condition(self, guard: GuardCondition) -> bool:
        """Drop ``guard``; False if it is not this node's."""
        if guard not in self._guards:
            return False
        guard.destroy()
        self._guards.remove(guard)
        return True

    def destroy_rate(self, rate: Rate) -> bool:
        """Drop ``rate``."""
        rate.destroy()
        return True
