"""Calls ``toggle``: with ``call_async`` and ``spin_until_future_complete``, then from a
coroutine timer callback that awaits the call (the client in a group of its own, so that the
response can be taken while the timer's group waits, as rclpy needs)."""

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rclpy.node import Node
from std_srvs.srv import SetBool


def main() -> None:
    rclpy.init()
    node = Node("caller")
    client = node.create_client(SetBool, "toggle", callback_group=MutuallyExclusiveCallbackGroup())
    client.wait_for_service()  # however long the server takes to start (a busy machine)
    future = client.call_async(SetBool.Request(data=True))
    rclpy.spin_until_future_complete(node, future)
    response = future.result()
    node.get_logger().info(f"sync-style: success={response.success} message={response.message!r}")

    results = []

    async def ask() -> None:
        timer.cancel()
        answer = await client.call_async(SetBool.Request(data=False))
        node.get_logger().info(f"awaited: success={answer.success} message={answer.message!r}")
        results.append(answer)

    timer = node.create_timer(0.1, ask)
    while rclpy.ok() and not results:
        rclpy.spin_once(node, timeout_sec=1.0)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
