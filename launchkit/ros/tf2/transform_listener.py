"""tf2_ros' ``TransformListener``: fills a buffer from ``/tf`` and ``/tf_static``.

Its subscriptions belong to the node given (``/tf`` volatile and ``/tf_static`` transient
local, so a late listener still gets the latched static transforms, both depth 100 as in
tf2_ros), so whoever spins that node feeds the buffer; ``spin_thread=True`` spins it in a thread
of the listener's own instead.
"""

from __future__ import annotations

import importlib
import threading
from typing import Any

from launchkit.ros.executor import ExternalShutdownException
from launchkit.ros.executors import SingleThreadedExecutor
from launchkit.ros.msgs import get_message
from launchkit.ros.qos import DurabilityPolicy, HistoryPolicy, QoSProfile

#: tf2_ros' default QoS of the /tf subscription
DYNAMIC_LISTENER_QOS = QoSProfile(
    depth=100, durability=DurabilityPolicy.VOLATILE, history=HistoryPolicy.KEEP_LAST
)
#: tf2_ros' default QoS of the /tf_static subscription
STATIC_LISTENER_QOS = QoSProfile(
    depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST
)
_AUTHORITY = "default_authority"
_SPIN_PERIOD = 0.1  # how often the dedicated thread looks whether it should stop (s)


def _reentrant_group() -> Any:
    """A reentrant callback group, as tf2_ros gives its subscriptions: a lookup waiting in
    another callback of a multi-threaded executor still gets the data. None (the node's default
    group) while ``launchkit.ros`` has no ``callback_groups`` module."""
    try:
        groups = importlib.import_module("launchkit.ros.callback_groups")
    except ImportError:
        return None
    return groups.ReentrantCallbackGroup()


class TransformListener:
    """Subscribes ``node`` to ``/tf`` and ``/tf_static`` and adds what arrives to ``buffer``."""

    def __init__(
        self,
        buffer: Any,
        node: Any,
        *,
        spin_thread: bool = False,
        qos: QoSProfile | int | None = None,
        static_qos: QoSProfile | int | None = None,
    ) -> None:
        self.buffer = buffer
        self.node = node
        message = get_message("tf2_msgs/msg/TFMessage")
        self.group = _reentrant_group()
        self.tf_sub = node.create_subscription(
            message,
            "/tf",
            self.callback,
            DYNAMIC_LISTENER_QOS if qos is None else qos,
            callback_group=self.group,
        )
        self.tf_static_sub = node.create_subscription(
            message,
            "/tf_static",
            self.static_callback,
            STATIC_LISTENER_QOS if static_qos is None else static_qos,
            callback_group=self.group,
        )
        if spin_thread:
            self.executor = SingleThreadedExecutor(context=node.context)
            self._stop = threading.Event()
            self.dedicated_listener_thread = threading.Thread(
                target=self._spin, name="tf2_listener", daemon=True
            )
            self.dedicated_listener_thread.start()

    def _spin(self) -> None:
        self.executor.add_node(self.node)
        try:
            while not self._stop.is_set() and self.node.context.ok():
                self.executor.spin_once(timeout_sec=_SPIN_PERIOD)
        except ExternalShutdownException:
            pass  # the context was shut down while waiting: the thread's work is over
        finally:
            self.executor.remove_node(self.node)

    def __del__(self) -> None:
        thread = getattr(self, "dedicated_listener_thread", None)
        if thread is not None:
            self._stop.set()
            if thread is not threading.current_thread():
                thread.join()
        if hasattr(self, "tf_static_sub"):
            self.unregister()

    def unregister(self) -> None:
        """Unsubscribe from ``/tf`` and ``/tf_static``."""
        self.node.destroy_subscription(self.tf_sub)
        self.node.destroy_subscription(self.tf_static_sub)

    def callback(self, data: Any) -> None:
        """Add the transforms of a ``/tf`` message."""
        for transform in data.transforms:
            self.buffer.set_transform(transform, _AUTHORITY)

    def static_callback(self, data: Any) -> None:
        """Add the transforms of a ``/tf_static`` message as static."""
        for transform in data.transforms:
            self.buffer.set_transform_static(transform, _AUTHORITY)
