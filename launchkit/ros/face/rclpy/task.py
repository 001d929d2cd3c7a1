"""``rclpy.task``: futures and the tasks executors run (coroutines included)."""

from launchkit.ros.task import Future, FutureState, Task

__all__ = ["Future", "FutureState", "Task"]
