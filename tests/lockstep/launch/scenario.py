"""The repeatable scenario's two nodes, on the launch's simulated clock.

``driver``: publishes /cmd_vel from a 10 Hz timer: forward and turning from 0.5 s to 2.5 s of
simulated time, then stopped. ``printer``: keeps the latest /odom and prints its stamp and pose,
every float in full, when its timer reaches the simulated time given as argument.
``camera`` (a benchmark's): counts the camera's frames and prints the count every simulated
second.
"""

import sys

import rclpy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rclpy.node import Node
from ticker import spin_until_stopped  # beside this file


def driver(node: Node) -> None:
    pub = node.create_publisher(Twist, "/cmd_vel", 10)

    def drive() -> None:
        now = node.get_clock().now().nanoseconds / 1e9
        twist = Twist()
        if 0.5 <= now < 2.5:
            twist.linear.x = 0.5
            twist.angular.z = 0.4
        pub.publish(twist)

    node.create_timer(0.1, drive)


def printer(node: Node, at: float) -> None:
    latest: list[Odometry] = []

    def keep(msg: Odometry) -> None:
        latest[:] = [msg]

    node.create_subscription(Odometry, "/odom", keep, 10)
    done: list[bool] = []

    def show() -> None:
        if done or node.get_clock().now().nanoseconds < at * 1e9:
            return
        done.append(True)
        if not latest:
            print("ODOM none", flush=True)
            return
        odom = latest[0]
        p, q = odom.pose.pose.position, odom.pose.pose.orientation
        values = (p.x, p.y, p.z, q.x, q.y, q.z, q.w)
        stamp = odom.header.stamp.sec * 10**9 + odom.header.stamp.nanosec
        print(f"ODOM at {stamp}: " + " ".join(v.hex() for v in values), flush=True)

    node.create_timer(0.05, show)


def camera(node: Node) -> None:
    from sensor_msgs.msg import Image

    frames = [0]

    def count(_msg: Image) -> None:
        frames[0] += 1

    node.create_subscription(Image, "/camera1/image_raw", count, 5)

    def show() -> None:
        now = node.get_clock().now().nanoseconds
        print(f"FRAMES {frames[0]} at {now}", flush=True)

    node.create_timer(1.0, show)


def main() -> None:
    rclpy.init()
    role = sys.argv[1]
    node = Node(role)
    if role == "driver":
        driver(node)
    elif role == "camera":
        camera(node)
    else:
        printer(node, float(sys.argv[2]))
    spin_until_stopped(node)


if __name__ == "__main__":
    main()
