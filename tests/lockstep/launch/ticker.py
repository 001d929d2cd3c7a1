"""A node whose sim-time timer publishes a count (``ticker``), or whose loop does on a
``Rate`` (``rater``), or whose timer callback never returns (``stuck``); another that prints what it hears, with its own clock's time. All run
on the launch's clock."""

import sys
import threading
import time

import rclpy
from rclpy.node import Node
from std_msgs.msg import Int64


def main() -> None:
    rclpy.init()
    role = sys.argv[1]
    node = Node(role)
    if role == "ticker":
        pub = node.create_publisher(Int64, "ticks", 10)
        count = [0]

        def tick() -> None:
            count[0] += 1
            pub.publish(Int64(data=count[0]))
            print(f"tick {count[0]} at {node.get_clock().now().nanoseconds}", flush=True)

        node.create_timer(0.25, tick)
    elif role == "stuck":  # its callback at 0.5 s never returns: the time stands there

        def hang() -> None:
            print("hanging at", node.get_clock().now().nanoseconds, flush=True)
            time.sleep(3600)

        node.create_timer(0.5, hang)
    elif role == "rater":
        pub = node.create_publisher(Int64, "ticks", 10)
        threading.Thread(target=rclpy.spin, args=(node,), daemon=True).start()
        rate = node.create_rate(4.0)
        count = 0
        while rclpy.ok():
            rate.sleep()
            count += 1
            pub.publish(Int64(data=count))
            print(f"tick {count} at {node.get_clock().now().nanoseconds}", flush=True)
    else:

        def heard(msg: Int64) -> None:
            print(f"heard {msg.data} at {node.get_clock().now().nanoseconds}", flush=True)

        node.create_subscription(Int64, "ticks", heard, 10)
    spin_until_stopped(node)


def spin_until_stopped(node: Node) -> None:
    """Spin ``node`` until Ctrl-C or SIGTERM."""
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
