"""One of two clients sending a goal to the Fibonacci server at the same time (its order from
the command line): it sees its own goal's feedback only."""

import sys
import time

import rclpy
from fibonacci_type import Fibonacci
from rclpy.action import ActionClient
from rclpy.node import Node


def main() -> None:
    order = int(sys.argv[1])
    rclpy.init()
    node = Node(f"racer_{order}")
    client = ActionClient(node, Fibonacci, "fibonacci")
    client.wait_for_server()
    lengths: list[int] = []
    goal = client.send_goal_async(
        Fibonacci.Goal(order=order),
        feedback_callback=lambda message: lengths.append(len(message.feedback.sequence)),
    )
    rclpy.spin_until_future_complete(node, goal)
    result = goal.result().get_result_async()
    rclpy.spin_until_future_complete(node, result)
    deadline = time.monotonic() + 60.0
    while len(lengths) < order - 1 and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    # the other client's feedback is never delivered here: one message per step of this goal
    print(f"order {order}: feedback lengths {lengths}")
    print(f"order {order}: result {list(result.result().result.sequence)}")
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
