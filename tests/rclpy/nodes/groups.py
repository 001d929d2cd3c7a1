"""A MultiThreadedExecutor runs two slow timers of a reentrant group at once, and two of a
mutually exclusive group one at a time."""

import threading
import time

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node


def main() -> None:
    rclpy.init()
    node = Node("groups")
    lock = threading.Lock()
    running = {"exclusive": 0, "reentrant": 0}
    most = {"exclusive": 0, "reentrant": 0}
    calls = {"exclusive": 0, "reentrant": 0}

    def slow(kind: str):
        def callback() -> None:
            with lock:
                running[kind] += 1
                most[kind] = max(most[kind], running[kind])
                calls[kind] += 1
            time.sleep(0.3)
            with lock:
                running[kind] -= 1

        return callback

    exclusive = MutuallyExclusiveCallbackGroup()
    reentrant = ReentrantCallbackGroup()
    for _ in range(2):
        node.create_timer(0.05, slow("exclusive"), callback_group=exclusive)
        node.create_timer(0.05, slow("reentrant"), callback_group=reentrant)
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(node)
    while min(calls.values()) < 6:
        executor.spin_once(timeout_sec=0.1)
    executor.shutdown()
    print("mutually exclusive group ran one at a time:", most["exclusive"] == 1)
    print("reentrant group ran callbacks together:", most["reentrant"] >= 2)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
