"""Test program: the graph an rmw_zenoh action server and client announce for action
``/fibonacci`` (example_interfaces/action/Fibonacci), as liveliness tokens on the router: node
``/fib_server`` with the action's three services and its feedback and status publishers, node
``/fib_client`` with the matching clients and subscriptions. launchkit has no actions yet; what
``node info`` makes of an action is read from these tokens alone, as rcl_action reads it."""

import os
import signal
import threading

from launchkit.envvars import ROUTER
from launchkit.ros.keyexpr import entity_token, node_token
from launchkit.ros.qos import QoSProfile
from launchkit.ros.session import client_config, close_session, open_session

ACTION = "/fibonacci"
TYPE = "example_interfaces/action/Fibonacci"
HASH = "RIHS01_" + "0" * 64
SERVICES = ("send_goal", "cancel_goal", "get_result")
SERVICE_TYPES = {
    "send_goal": f"{TYPE}_SendGoal",
    "cancel_goal": "action_msgs/srv/CancelGoal",
    "get_result": f"{TYPE}_GetResult",
}
TOPICS = {"feedback": f"{TYPE}_FeedbackMessage", "status": "action_msgs/msg/GoalStatusArray"}


def keys(domain: int, zid: str, node_id: int, name: str, server: bool) -> list[str]:
    """The node's token and its entities' tokens."""
    found = [node_token(domain, zid, node_id, "/", "/", name)]
    entities = [
        ("SS" if server else "SC", f"{ACTION}/_action/{s}", SERVICE_TYPES[s]) for s in SERVICES
    ] + [("MP" if server else "MS", f"{ACTION}/_action/{t}", TOPICS[t]) for t in TOPICS]
    for number, (kind, topic, type_name) in enumerate(entities, start=1):
        found.append(
            entity_token(
                domain,
                zid,
                node_id,
                node_id * 100 + number,
                kind,
                "/",
                "/",
                name,
                topic,
                type_name,
                HASH,
                QoSProfile(depth=10),
            )
        )
    return found


def main() -> None:
    domain = int(os.environ.get("ROS_DOMAIN_ID", "0") or 0)
    session = open_session(client_config(os.environ[ROUTER]))
    zid = str(session.zid())
    announced = keys(domain, zid, 1, "fib_server", True) + keys(domain, zid, 2, "fib_client", False)
    tokens = [session.liveliness().declare_token(key) for key in announced]
    stop = threading.Event()
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    print("action_graph ready", flush=True)
    stop.wait()
    for token in tokens:
        token.undeclare()
    close_session(session)


if __name__ == "__main__":
    main()
