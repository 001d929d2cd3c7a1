"""``rclpy.lifecycle``: managed nodes."""

from launchkit.ros.lifecycle import (
    LifecycleNode,
    ManagedEntity,
    SimpleManagedEntity,
    State,
    TransitionCallbackReturn,
)

LifecycleState = State

__all__ = [
    "LifecycleNode",
    "LifecycleState",
    "ManagedEntity",
    "SimpleManagedEntity",
    "State",
    "TransitionCallbackReturn",
]
