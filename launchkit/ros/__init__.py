"""launchkit.ros: an rclpy-like ROS 2 node API over Zenoh, with the real ROS 2 message types.

::

    import launchkit.ros as ros
    from launchkit.ros.msgs.std_msgs.msg import String

    ros.init()
    node = ros.Node("talker")
    pub = node.create_publisher(String, "chatter", 10)
    node.create_timer(0.5, lambda: pub.publish(String(data="hello")))
    ros.spin(node)
    ros.shutdown()

Nodes connect to the Zenoh router at ``$LAUNCHKIT_ROUTER`` (default tcp/127.0.0.1:7447, the one
``launchkit run`` hosts) and follow rmw_zenoh's wire conventions.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes

if TYPE_CHECKING:
    from launchkit.ros.clock import Clock, ClockType, Duration, ROSClock, Time
    from launchkit.ros.context import Context, NotInitializedError
    from launchkit.ros.context import default_context as default_context
    from launchkit.ros.executor import (
        Executor,
        ExternalShutdownException,
        MultiThreadedExecutor,
        SingleThreadedExecutor,
        spin,
        spin_once,
        spin_until_future_complete,
    )
    from launchkit.ros.logging import LoggingSeverity, get_logger
    from launchkit.ros.node import Node
    from launchkit.ros.node_params import (
        InvalidParameterTypeException,
        ParameterAlreadyDeclaredException,
        ParameterNotDeclaredException,
        SetParametersResult,
    )
    from launchkit.ros.params import Parameter, ParameterType
    from launchkit.ros.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        QoSProfile,
        ReliabilityPolicy,
        qos_profile_sensor_data,
        qos_profile_system_default,
    )
    from launchkit.ros.task import Future

# Names are imported on first use (PEP 562): importing one submodule, e.g. launchkit.ros.keyexpr
# for the command-line tools, must not load the message types, numpy and the whole node API.
_LAZY = {
    "Clock": "launchkit.ros.clock",
    "ClockType": "launchkit.ros.clock",
    "Duration": "launchkit.ros.clock",
    "ROSClock": "launchkit.ros.clock",
    "Time": "launchkit.ros.clock",
    "Context": "launchkit.ros.context",
    "NotInitializedError": "launchkit.ros.context",
    "default_context": "launchkit.ros.context",
    "Executor": "launchkit.ros.executor",
    "ExternalShutdownException": "launchkit.ros.executor",
    "MultiThreadedExecutor": "launchkit.ros.executor",
    "SingleThreadedExecutor": "launchkit.ros.executor",
    "spin": "launchkit.ros.executor",
    "spin_once": "launchkit.ros.executor",
    "spin_until_future_complete": "launchkit.ros.executor",
    "LoggingSeverity": "launchkit.ros.logging",
    "get_logger": "launchkit.ros.logging",
    "Node": "launchkit.ros.node",
    "InvalidParameterTypeException": "launchkit.ros.node_params",
    "ParameterAlreadyDeclaredException": "launchkit.ros.node_params",
    "ParameterNotDeclaredException": "launchkit.ros.node_params",
    "SetParametersResult": "launchkit.ros.node_params",
    "Parameter": "launchkit.ros.params",
    "ParameterType": "launchkit.ros.params",
    "DurabilityPolicy": "launchkit.ros.qos",
    "HistoryPolicy": "launchkit.ros.qos",
    "QoSProfile": "launchkit.ros.qos",
    "ReliabilityPolicy": "launchkit.ros.qos",
    "qos_profile_sensor_data": "launchkit.ros.qos",
    "qos_profile_system_default": "launchkit.ros.qos",
    "Future": "launchkit.ros.task",
    "QoSDurabilityPolicy": "launchkit.ros.qos:DurabilityPolicy",
    "QoSReliabilityPolicy": "launchkit.ros.qos:ReliabilityPolicy",
    "QoSHistoryPolicy": "launchkit.ros.qos:HistoryPolicy",
}


# the public names of the node API, imported when first asked for
__getattr__ = lazy_attributes(__name__, _LAZY, globals())


if TYPE_CHECKING:
    QoSDurabilityPolicy = DurabilityPolicy
    QoSReliabilityPolicy = ReliabilityPolicy
    QoSHistoryPolicy = HistoryPolicy


def init(
    args: list[str] | None = None, *, context: Context | None = None, domain_id: int | None = None
) -> None:
    """Initialize ROS for this process: parse ``--ros-args`` of ``args`` (default sys.argv).

    Installs SIGINT/SIGTERM handlers (main thread only) that shut down the default context,
    which makes ``spin`` return so that the node exits promptly.
    """
    from launchkit.ros.context import default_context, install_signal_handlers

    (context or default_context).init(args, domain_id)
    if context is None or context is default_context:
        install_signal_handlers()


def ok(*, context: Context | None = None) -> bool:
    """True between ``init()`` and ``shutdown()`` (a SIGINT shuts down)."""
    from launchkit.ros.context import default_context

    return (context or default_context).ok()


def shutdown(*, context: Context | None = None) -> None:
    """Destroy every entity and close the Zenoh session (safe to call twice)."""
    from launchkit.ros.context import default_context

    (context or default_context).shutdown()


try_shutdown = shutdown


def create_node(node_name: str, **kwargs: object) -> Node:
    """rclpy's ``create_node``: same as ``Node(node_name, ...)``."""
    from launchkit.ros.node import Node

    return Node(node_name, **kwargs)  # type: ignore[arg-type]


__all__ = [
    "Clock",
    "ClockType",
    "Context",
    "DurabilityPolicy",
    "Duration",
    "Executor",
    "ExternalShutdownException",
    "Future",
    "HistoryPolicy",
    "InvalidParameterTypeException",
    "LoggingSeverity",
    "MultiThreadedExecutor",
    "Node",
    "NotInitializedError",
    "Parameter",
    "ParameterAlreadyDeclaredException",
    "ParameterNotDeclaredException",
    "ParameterType",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ROSClock",
    "ReliabilityPolicy",
    "SetParametersResult",
    "SingleThreadedExecutor",
    "Time",
    "create_node",
    "get_logger",
    "init",
    "ok",
    "qos_profile_sensor_data",
    "qos_profile_system_default",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
]
