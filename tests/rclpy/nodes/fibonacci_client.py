"""A client of the Fibonacci action server: a goal with feedback, a rejected goal, a goal it
cancels, an aborted goal, and the action as the graph shows it."""

import time

import rclpy
from fibonacci_type import Fibonacci
from rclpy.action import ActionClient, get_action_names_and_types
from rclpy.node import Node

PATIENCE = 60.0


def main() -> None:
    rclpy.init()
    node = Node("fibonacci_client")
    client = ActionClient(node, Fibonacci, "fibonacci")
    client.wait_for_server()
    print(f"server ready: {client.server_is_ready()}")
    actions = get_action_names_and_types(node)
    print(f"actions: {[(n, [t.endswith('/action/Fibonacci') for t in ts]) for n, ts in actions]}")

    def spin_until(condition) -> None:  # type: ignore[no-untyped-def]
        deadline = time.monotonic() + PATIENCE
        while not condition() and time.monotonic() < deadline:
            rclpy.spin_once(node, timeout_sec=0.1)

    def send(order: int, feedback_callback=None):  # type: ignore[no-untyped-def]
        future = client.send_goal_async(
            Fibonacci.Goal(order=order), feedback_callback=feedback_callback
        )
        rclpy.spin_until_future_complete(node, future)
        return future.result()

    def result_of(goal_handle):  # type: ignore[no-untyped-def]
        future = goal_handle.get_result_async()
        rclpy.spin_until_future_complete(node, future)
        return future.result()

    feedback: list[list[int]] = []
    goal_handle = send(5, lambda message: feedback.append(list(message.feedback.sequence)))
    print(f"order 5: accepted {goal_handle.accepted}")
    response = result_of(goal_handle)
    spin_until(lambda: len(feedback) == 4 and goal_handle.status == 4)
    for sequence in feedback:
        print(f"feedback: {sequence}")
    print(f"result: status {response.status} sequence {list(response.result.sequence)}")
    print(f"goal handle status: {goal_handle.status}")

    print(f"order -1: accepted {send(-1).accepted}")

    held: list[list[int]] = []
    goal_handle = send(1000, lambda message: held.append(list(message.feedback.sequence)))
    spin_until(lambda: bool(held))
    future = goal_handle.cancel_goal_async()
    rclpy.spin_until_future_complete(node, future)
    cancel = future.result()
    canceling = [
        bytes(g.goal_id.uuid) == bytes(goal_handle.goal_id.uuid) for g in cancel.goals_canceling
    ]
    print(f"cancel: return code {cancel.return_code}, canceling this goal {canceling}")
    response = result_of(goal_handle)
    print(f"result: status {response.status} sequence {list(response.result.sequence)}")

    response = result_of(send(13))
    print(f"order 13: status {response.status} sequence {list(response.result.sequence)}")

    future = goal_handle.cancel_goal_async()
    rclpy.spin_until_future_complete(node, future)
    print(f"cancel an ended goal: return code {future.result().return_code}")
    client.destroy()
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
