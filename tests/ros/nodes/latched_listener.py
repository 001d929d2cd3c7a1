"""Test node: a transient-local subscription (an advanced subscriber); exits without shutdown().

Without launchkit closing every session at exit, zenoh would hang this process at exit.
"""

from launchkit.ros.msgs.std_msgs.msg import String

import launchkit.ros as ros


def main() -> None:
    ros.init()
    node = ros.Node("latched_listener")
    qos = ros.QoSProfile(depth=1, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(
        String, "/robot_description", lambda m: print(f"got: {m.data}", flush=True), qos
    )
    pub = node.create_publisher(String, "/status", qos)
    pub.publish(String(data="up"))
    try:
        print("latched_listener ready", flush=True)
        ros.spin(node)
    except (KeyboardInterrupt, ros.ExternalShutdownException):
        pass
    print("latched_listener done", flush=True)


if __name__ == "__main__":
    main()
