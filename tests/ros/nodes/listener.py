"""Test node: prints every std_msgs/String it gets on ``chatter`` as ``heard: DATA``."""

from launchkit.ros.msgs.std_msgs.msg import String

import launchkit.ros as ros


def main() -> None:
    ros.init()
    node = ros.Node("listener")
    node.create_subscription(String, "chatter", lambda m: print(f"heard: {m.data}", flush=True), 10)
    try:
        print("listener ready", flush=True)
        ros.spin(node)
    except (KeyboardInterrupt, ros.ExternalShutdownException):
        pass
    ros.try_shutdown()
    print("listener done", flush=True)


if __name__ == "__main__":
    main()
