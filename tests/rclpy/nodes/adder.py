"""Serves ``toggle`` (std_srvs/SetBool), answering "set to DATA", until stopped."""

import rclpy
from rclpy.node import Node
from std_srvs.srv import SetBool


def main() -> None:
    rclpy.init()
    node = Node("toggler")

    def toggle(request: SetBool.Request, response: SetBool.Response) -> SetBool.Response:
        node.get_logger().info(f"Incoming request: {request.data}")
        response.success = request.data
        response.message = f"set to {request.data}"
        return response

    node.create_service(SetBool, "toggle", toggle)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
