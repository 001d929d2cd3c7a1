"""An action server of Fibonacci: rejects a negative order, aborts order 13, and holds order
1000 until a client cancels it; its callbacks in a reentrant group of a MultiThreadedExecutor
(so a cancel request is served while a goal executes), the execute callback a coroutine."""

import time

import rclpy
from fibonacci_type import Fibonacci
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile

UNLUCKY = 13
UNTIL_CANCELED = 1000
PATIENCE = 60.0


def main() -> None:
    rclpy.init()
    node = Node("fibonacci_server")
    log = node.get_logger()

    def on_goal(goal: Fibonacci.Goal) -> GoalResponse:
        log.info(f"goal request: order {goal.order}")
        return GoalResponse.REJECT if goal.order < 0 else GoalResponse.ACCEPT

    def on_cancel(goal_handle) -> CancelResponse:  # type: ignore[no-untyped-def]
        log.info(f"cancel request: order {goal_handle.request.order}")
        return CancelResponse.ACCEPT

    async def execute(goal_handle) -> Fibonacci.Result:  # type: ignore[no-untyped-def]
        order = goal_handle.request.order
        log.info(f"executing: order {order}, status {goal_handle.status}")
        feedback = Fibonacci.Feedback(sequence=[0, 1])
        if order == UNLUCKY:
            goal_handle.abort()
            log.info(f"aborted: active {goal_handle.is_active}")
            return Fibonacci.Result()
        if order == UNTIL_CANCELED:
            goal_handle.publish_feedback(feedback)
            deadline = time.monotonic() + PATIENCE
            while not goal_handle.is_cancel_requested and time.monotonic() < deadline:
                time.sleep(0.01)
            goal_handle.canceled()
            log.info(f"canceled: status {goal_handle.status}")
            return Fibonacci.Result(sequence=feedback.sequence)
        for i in range(1, order):
            feedback.sequence.append(feedback.sequence[i] + feedback.sequence[i - 1])
            goal_handle.publish_feedback(feedback)
        goal_handle.succeed()
        log.info(f"succeeded: {list(feedback.sequence)}")
        return Fibonacci.Result(sequence=feedback.sequence)

    ActionServer(
        node,
        Fibonacci,
        "fibonacci",
        execute,
        goal_callback=on_goal,
        cancel_callback=on_cancel,
        callback_group=ReentrantCallbackGroup(),
        feedback_pub_qos_profile=QoSProfile(depth=100),  # two goals' feedback at once
    )
    print("serving", flush=True)
    try:
        rclpy.spin(node, executor=MultiThreadedExecutor(num_threads=4))
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
