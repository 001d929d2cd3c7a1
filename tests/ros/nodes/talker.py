"""Test node: publishes std_msgs/String "hello N" on ``chatter`` at 50 Hz."""

from launchkit.ros.msgs.std_msgs.msg import String

import launchkit.ros as ros


def main() -> None:
    ros.init()
    node = ros.Node("talker")
    pub = node.create_publisher(String, "chatter", 10)
    count = [0]

    def tick() -> None:
        count[0] += 1
        pub.publish(String(data=f"hello {count[0]}"))

    node.create_timer(0.02, tick)
    try:  # Ctrl-C may come at any point from here: the node ends normally, as an rclpy node
        print("talker ready", flush=True)
        ros.spin(node)
    except (KeyboardInterrupt, ros.ExternalShutdownException):
        pass
    node.destroy_node()
    ros.try_shutdown()
    print("talker done", flush=True)


if __name__ == "__main__":
    main()
