"""Spins with nothing around it: Ctrl-C ends it with Python's KeyboardInterrupt."""

import rclpy
from rclpy.node import Node

rclpy.init()
node = Node("uncaught")
timer = node.create_timer(0.1, lambda: (timer.cancel(), print("spinning", flush=True)))
rclpy.spin(node)
