"""rclpy, as launchkit provides it: the same API over launchkit's ROS layer (Zenoh, rmw_zenoh's
wire format). Every name here is :mod:`launchkit.ros`'s; submodules load when first used."""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

from launchkit.ros import (
    create_node,
    get_global_executor,
    init,
    ok,
    shutdown,
    spin,
    spin_once,
    spin_until_future_complete,
    try_shutdown,
)
from launchkit.ros.context import Context
from launchkit.ros.params import Parameter
from launchkit.ros.signals import (
    SignalHandlerOptions,
    install_signal_handlers,
    uninstall_signal_handlers,
)
from launchkit.ros.task import Future

__all__ = [
    "Context",
    "Future",
    "Parameter",
    "SignalHandlerOptions",
    "create_node",
    "get_global_executor",
    "get_rmw_implementation_identifier",
    "init",
    "install_signal_handlers",
    "ok",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
    "uninstall_signal_handlers",
]


def get_rmw_implementation_identifier() -> str:
    """The middleware: launchkit speaks rmw_zenoh's wire format."""
    return "rmw_zenoh_cpp"


def __getattr__(name: str) -> ModuleType | Any:
    # rclpy's submodules (rclpy.executors, rclpy.qos...) as attributes, loaded on first use
    try:
        return importlib.import_module(f"{__name__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
