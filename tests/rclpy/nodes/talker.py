"""Publishes "Hello World: N" on ``chatter`` five times, once a subscription has matched."""

import sys

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    def __init__(self) -> None:
        super().__init__("talker")
        self.publisher = self.create_publisher(String, "chatter", 10)
        self.count = 0
        self.timer = self.create_timer(0.1, self.tick)

    def tick(self) -> None:
        if self.publisher.get_subscription_count() == 0:
            return
        msg = String()
        msg.data = f"Hello World: {self.count}"
        self.publisher.publish(msg)
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.count += 1
        if self.count == 5:
            self.timer.cancel()


def main() -> None:
    rclpy.init()
    node = Talker()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    except ExternalShutdownException:
        sys.exit(1)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
