"""One of two clients sending a goal to the Fibonacci server at the same time (its order from
the command line): the feedback callback of its goal gets that goal's feedback only."""

import sys
import uuid

import rclpy
from fibonacci_type import Fibonacci
from rclpy.action import ActionClient
from rclpy.node import Node
from rclpy.qos import QoSProfile
from unique_identifier_msgs.msg import UUID


def main() -> None:
    order = int(sys.argv[1])
    rclpy.init()
    node = Node(f"racer_{order}")
    # every client receives every goal's feedback (it keeps its own goal's): room for both
    # goals' messages, so that none is pushed out while this process is slow (a busy machine)
    client = ActionClient(
        node, Fibonacci, "fibonacci", feedback_sub_qos_profile=QoSProfile(depth=100)
    )
    client.wait_for_server()
    mine = UUID(uuid=list(uuid.uuid4().bytes))
    foreign: list[bytes] = []

    def on_feedback(message) -> None:  # type: ignore[no-untyped-def]
        if bytes(message.goal_id.uuid) != bytes(mine.uuid):
            foreign.append(bytes(message.goal_id.uuid))

    goal = client.send_goal_async(
        Fibonacci.Goal(order=order), feedback_callback=on_feedback, goal_uuid=mine
    )
    rclpy.spin_until_future_complete(node, goal)
    result = goal.result().get_result_async()
    rclpy.spin_until_future_complete(node, result)
    print(f"order {order}: feedback of other goals {len(foreign)}")
    print(f"order {order}: result {list(result.result().result.sequence)}")
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
