"""Spins until stopped; says how: Ctrl-C (KeyboardInterrupt) or a shutdown from outside
(ExternalShutdownException), as the ROS 2 examples handle them."""

import sys

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


def main() -> None:
    rclpy.init()
    node = Node("stoppable")

    def tick() -> None:  # once, from inside spin(); then spin() waits with nothing to do
        timer.cancel()
        print("spinning", flush=True)

    timer = node.create_timer(0.1, tick)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        print("KeyboardInterrupt; ok():", rclpy.ok(), flush=True)
    except ExternalShutdownException:
        print("ExternalShutdownException; ok():", rclpy.ok(), flush=True)
        sys.exit(1)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    print("done", flush=True)


if __name__ == "__main__":
    main()
