"""Test node for ``node info``'s hidden names: ``/hider`` with a visible topic ``/shown``, a
hidden topic ``/_private/state``, a hidden service ``/hider/_secret`` (std_srvs/srv/Trigger),
and a hidden node ``/_helper`` in the same process (hidden names have a part starting with
``_``, as ros2 judges them)."""

from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.std_srvs.srv import Trigger

import launchkit.ros as ros


def main() -> None:
    ros.init()
    hider = ros.Node("hider")
    helper = ros.Node("_helper")
    hider.create_publisher(String, "/shown", 10)
    hider.create_publisher(String, "/_private/state", 10)
    hider.create_service(Trigger, "~/_secret", lambda request, response: response)
    helper.create_subscription(String, "/shown", lambda msg: None, 10)
    print("hidden_parts ready", flush=True)
    executor = ros.SingleThreadedExecutor()
    executor.add_node(hider)
    executor.add_node(helper)
    try:
        executor.spin()
    except (KeyboardInterrupt, ros.ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
