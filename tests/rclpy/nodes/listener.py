"""Prints the first five messages on ``chatter``, with their count of publishers, and exits."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import String


def main() -> None:
    rclpy.init()
    node = Node("listener")
    heard = []

    def on_message(msg: String) -> None:
        node.get_logger().info(f'I heard: "{msg.data}"')
        heard.append(msg.data)

    node.create_subscription(String, "chatter", on_message, 10)
    while rclpy.ok() and len(heard) < 5:
        rclpy.spin_once(node, timeout_sec=0.5)
    print("publishers on chatter:", node.count_publishers("chatter"))
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
