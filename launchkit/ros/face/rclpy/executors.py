"""``rclpy.executors``: which thread runs the callbacks."""

from launchkit.ros.executor import (
    ConditionReachedException,
    Executor,
    ExternalShutdownException,
    ShutdownException,
    TimeoutException,
)
from launchkit.ros.executors import MultiThreadedExecutor, SingleThreadedExecutor
from launchkit.ros.task import await_or_execute

__all__ = [
    "ConditionReachedException",
    "Executor",
    "ExternalShutdownException",
    "MultiThreadedExecutor",
    "ShutdownException",
    "SingleThreadedExecutor",
    "TimeoutException",
    "await_or_execute",
]
