"""The managed-node state machine of ROS 2 (rcl_lifecycle's default one), without ROS.

Primary states ``unconfigured``, ``inactive``, ``active``, ``finalized``; a request
(``configure``, ``cleanup``, ``activate``, ``deactivate``, ``shutdown``) moves to a transition
state (``configuring`` ...), whose callback's result (success, failure, error) moves on to a
primary state, or through ``errorprocessing``. Ids and labels are lifecycle_msgs'.
"""

from __future__ import annotations

from dataclasses import dataclass

# lifecycle_msgs/msg/State
UNKNOWN, UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED = 0, 1, 2, 3, 4
CONFIGURING, CLEANINGUP, SHUTTINGDOWN, ACTIVATING, DEACTIVATING, ERRORPROCESSING = range(10, 16)

STATE_LABELS = {
    UNKNOWN: "unknown",
    UNCONFIGURED: "unconfigured",
    INACTIVE: "inactive",
    ACTIVE: "active",
    FINALIZED: "finalized",
    CONFIGURING: "configuring",
    CLEANINGUP: "cleaningup",
    SHUTTINGDOWN: "shuttingdown",
    ACTIVATING: "activating",
    DEACTIVATING: "deactivating",
    ERRORPROCESSING: "errorprocessing",
}

# lifecycle_msgs/msg/Transition: requests, and the callback results that end them
CONFIGURE, CLEANUP, ACTIVATE, DEACTIVATE = 1, 2, 3, 4
UNCONFIGURED_SHUTDOWN, INACTIVE_SHUTDOWN, ACTIVE_SHUTDOWN = 5, 6, 7
CALLBACK_SUCCESS, CALLBACK_FAILURE, CALLBACK_ERROR = 97, 98, 99


@dataclass(frozen=True)
class Transition:
    """One edge: ``id`` and ``label`` as published, from ``start`` to ``goal``."""

    id: int
    label: str
    start: int
    goal: int


def _results(base: int, name: str, state: int, success: int, failure: int) -> list[Transition]:
    return [
        Transition(base, f"{name}_success", state, success),
        Transition(base + 1, f"{name}_failure", state, failure),
        Transition(base + 2, f"{name}_error", state, ERRORPROCESSING),
    ]


#: Requests a primary state accepts: transition -> the transition state it enters.
REQUESTS = [
    Transition(CONFIGURE, "configure", UNCONFIGURED, CONFIGURING),
    Transition(CLEANUP, "cleanup", INACTIVE, CLEANINGUP),
    Transition(ACTIVATE, "activate", INACTIVE, ACTIVATING),
    Transition(DEACTIVATE, "deactivate", ACTIVE, DEACTIVATING),
    Transition(UNCONFIGURED_SHUTDOWN, "unconfigured_shutdown", UNCONFIGURED, SHUTTINGDOWN),
    Transition(INACTIVE_SHUTDOWN, "inactive_shutdown", INACTIVE, SHUTTINGDOWN),
    Transition(ACTIVE_SHUTDOWN, "active_shutdown", ACTIVE, SHUTTINGDOWN),
]

#: What a transition state's callback result leads to (success, failure, error, in order).
RESULTS = {
    CONFIGURING: _results(10, "configure", CONFIGURING, INACTIVE, UNCONFIGURED),
    CLEANINGUP: _results(20, "cleanup", CLEANINGUP, UNCONFIGURED, INACTIVE),
    ACTIVATING: _results(30, "activate", ACTIVATING, ACTIVE, INACTIVE),
    DEACTIVATING: _results(40, "deactivate", DEACTIVATING, INACTIVE, ACTIVE),
    SHUTTINGDOWN: _results(50, "shutdown", SHUTTINGDOWN, FINALIZED, FINALIZED),
    ERRORPROCESSING: [
        Transition(60, "errorprocessing_success", ERRORPROCESSING, UNCONFIGURED),
        Transition(61, "errorprocessing_failure", ERRORPROCESSING, FINALIZED),
        Transition(62, "errorprocessing_error", ERRORPROCESSING, FINALIZED),
    ],
}

#: Labels a request may be given by (``ros2 lifecycle set NODE shutdown``).
_SHUTDOWNS = (UNCONFIGURED_SHUTDOWN, INACTIVE_SHUTDOWN, ACTIVE_SHUTDOWN)


def available(state: int) -> list[Transition]:
    """The transitions leaving ``state`` (requests from a primary state, results from a
    transition state)."""
    if state in RESULTS:
        return list(RESULTS[state])
    return [t for t in REQUESTS if t.start == state]


def request(state: int, transition_id: int, label: str = "") -> Transition | None:
    """The request ``transition_id`` (or, when it is 0, ``label``) from ``state``; None when
    the state does not accept it. Any shutdown id means this state's shutdown, as ROS's
    ``shutdown`` does from every primary state."""
    for transition in available(state):
        if state in RESULTS:
            break
        if transition_id == 0 and label:
            if transition.label == label or (label == "shutdown" and transition.id in _SHUTDOWNS):
                return transition
        elif transition.id == transition_id or (
            transition_id in _SHUTDOWNS and transition.id in _SHUTDOWNS
        ):
            return transition
    return None


def result(state: int, outcome: int) -> Transition:
    """The edge leaving transition state ``state`` for callback ``outcome`` (97/98/99)."""
    index = {CALLBACK_SUCCESS: 0, CALLBACK_FAILURE: 1}.get(outcome, 2)
    return RESULTS[state][index]


def every_transition() -> list[Transition]:
    """The whole graph (``~/get_transition_graph``)."""
    return REQUESTS + [t for edges in RESULTS.values() for t in edges]
