"""launchkit.ros: rclpy's API and behaviour over Zenoh, with the real ROS 2 message types
(``import rclpy`` gets it through the face, :mod:`launchkit.ros.face`).

::

    import launchkit.ros as ros
    from launchkit.ros.msgs.std_msgs.msg import String

    ros.init()
    node = ros.Node("talker")
    pub = node.create_publisher(String, "chatter", 10)
    node.create_timer(0.5, lambda: pub.publish(String(data="hello")))
    try:
        ros.spin(node)
    except KeyboardInterrupt:  # Ctrl-C shuts ROS down and raises it, as in rclpy
        pass
    ros.try_shutdown()

Nodes connect to the Zenoh router at ``$LAUNCHKIT_ROUTER`` (default tcp/127.0.0.1:7447, the one
``launchkit run`` hosts) and follow rmw_zenoh's wire conventions.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit._lazy import lazy_attributes

if TYPE_CHECKING:
    from launchkit.ros.callback_groups import (
        CallbackGroup,
        MutuallyExclusiveCallbackGroup,
        ReentrantCallbackGroup,
    )
    from launchkit.ros.clock import Clock, ClockType, Duration, ROSClock, Time
    from launchkit.ros.context import Context, NotInitializedError, NotInitializedException
    from launchkit.ros.context import default_context as default_context
    from launchkit.ros.executor import Executor, ExternalShutdownException
    from launchkit.ros.executors import (
        MultiThreadedExecutor,
        SingleThreadedExecutor,
        get_global_executor,
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
    from launchkit.ros.signals import SignalHandlerOptions
    from launchkit.ros.task import Future

# Names are imported on first use (PEP 562): importing one submodule, e.g. launchkit.ros.keyexpr
# for the command-line tools, must not load the message types, numpy and the whole node API.
_LAZY = {
    "CallbackGroup": "launchkit.ros.callback_groups",
    "MutuallyExclusiveCallbackGroup": "launchkit.ros.callback_groups",
    "ReentrantCallbackGroup": "launchkit.ros.callback_groups",
    "Clock": "launchkit.ros.clock",
    "ClockType": "launchkit.ros.clock",
    "Duration": "launchkit.ros.clock",
    "ROSClock": "launchkit.ros.clock",
    "Time": "launchkit.ros.clock",
    "Context": "launchkit.ros.context",
    "NotInitializedError": "launchkit.ros.context",
    "NotInitializedException": "launchkit.ros.context",
    "default_context": "launchkit.ros.context",
    "Executor": "launchkit.ros.executor",
    "ExternalShutdownException": "launchkit.ros.executor",
    "MultiThreadedExecutor": "launchkit.ros.executors",
    "SingleThreadedExecutor": "launchkit.ros.executors",
    "get_global_executor": "launchkit.ros.executors",
    "spin": "launchkit.ros.executors",
    "spin_once": "launchkit.ros.executors",
    "spin_until_future_complete": "launchkit.ros.executors",
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
    "SignalHandlerOptions": "launchkit.ros.signals",
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
    args: list[str] | None = None,
    *,
    context: Context | None = None,
    domain_id: int | None = None,
    signal_handler_options: SignalHandlerOptions | None = None,
) -> None:
    """Initialize ROS for this process: parse ``--ros-args`` of ``args`` (default sys.argv).

    For the default context (unless ``signal_handler_options`` says otherwise) SIGINT and
    SIGTERM shut ROS down, as rclpy's handlers do: Ctrl-C then raises ``KeyboardInterrupt``
    in the main thread, and a spinning executor raises ``ExternalShutdownException`` after
    SIGTERM.
    """
    from launchkit.ros.context import default_context
    from launchkit.ros.signals import SignalHandlerOptions, install_signal_handlers

    context = context or default_context
    if signal_handler_options is None:
        signal_handler_options = (
            SignalHandlerOptions.ALL if context is default_context else SignalHandlerOptions.NO
        )
    context.init(args, domain_id)
    install_signal_handlers(signal_handler_options)


def ok(*, context: Context | None = None) -> bool:
    """True between ``init()`` and ``shutdown()`` (a signal shuts down)."""
    from launchkit.ros.context import default_context

    return (context or default_context).ok()


def shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    """Shut the context down: destroy every entity and close the Zenoh session.

    As rclpy: an error when the context is not initialized or was shut down already (a signal
    shuts it down: use :func:`try_shutdown` after catching ``KeyboardInterrupt``). The default
    context's signal handlers are put back.
    """
    from launchkit.ros.context import default_context
    from launchkit.ros.signals import uninstall_signal_handlers

    target = context or default_context
    try:
        target.shutdown()
    finally:
        if uninstall_handlers or (uninstall_handlers is None and target is default_context):
            uninstall_signal_handlers()


def try_shutdown(*, context: Context | None = None) -> None:
    """Shut the context down unless it is already (never an error)."""
    from launchkit.ros.context import default_context

    (context or default_context).try_shutdown()


def create_node(node_name: str, **kwargs: object) -> Node:
    """rclpy's ``create_node``: same as ``Node(node_name, ...)``."""
    from launchkit.ros.node import Node

    return Node(node_name, **kwargs)  # type: ignore[arg-type]


def remove_ros_args(args: list[str] | None = None) -> list[str]:
    """``args`` (default sys.argv) without its ``--ros-args`` sections."""
    import sys

    from launchkit.ros.arguments import remove_ros_args as remove

    return remove(sys.argv if args is None else list(args))


__all__ = [
    "CallbackGroup",
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
    "MutuallyExclusiveCallbackGroup",
    "Node",
    "NotInitializedError",
    "NotInitializedException",
    "Parameter",
    "ParameterAlreadyDeclaredException",
    "ParameterNotDeclaredException",
    "ParameterType",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ROSClock",
    "ReentrantCallbackGroup",
    "ReliabilityPolicy",
    "SetParametersResult",
    "SignalHandlerOptions",
    "SingleThreadedExecutor",
    "Time",
    "create_node",
    "get_global_executor",
    "get_logger",
    "init",
    "ok",
    "qos_profile_sensor_data",
    "qos_profile_system_default",
    "remove_ros_args",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
]
