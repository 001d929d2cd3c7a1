"""Placeholder."""

from launchkit.frontend.python.values import unsupported

LifecycleNode = unsupported("LifecycleNode")
LifecycleTransition = unsupported("LifecycleTransition")
ChangeState = unsupported("ChangeState")
StateTransition = unsupported("StateTransition")
OnStateTransition = unsupported("OnStateTransition")
State = unsupported("State")
Transition = unsupported("Transition")


def matches_node_name(name: str) -> None:
    """x"""
