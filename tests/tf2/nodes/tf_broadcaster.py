"""A node written against tf2_ros' API: ``odom -> base`` on /tf at 50 Hz, moving along x at
1 m/s (x is the stamp's seconds since ARGV[1], in nanoseconds), and ``base -> laser`` once,
latched on /tf_static."""

from __future__ import annotations

import math
import sys

from launchkit.ros.msgs.geometry_msgs.msg import TransformStamped
from tf2_ros import StaticTransformBroadcaster, TransformBroadcaster

import launchkit.ros as rclpy


def main() -> None:
    t0 = int(sys.argv[1])
    rclpy.init()
    node = rclpy.Node("tf_broadcaster")
    laser = TransformStamped()
    laser.header.stamp = node.get_clock().now().to_msg()
    laser.header.frame_id, laser.child_frame_id = "base", "laser"
    laser.transform.translation.x, laser.transform.translation.z = 0.5, 0.2
    laser.transform.rotation.z = laser.transform.rotation.w = math.sqrt(0.5)
    StaticTransformBroadcaster(node).sendTransform(laser)
    moving = TransformBroadcaster(node)

    def tick() -> None:
        now = node.get_clock().now()
        base = TransformStamped()
        base.header.stamp = now.to_msg()
        base.header.frame_id, base.child_frame_id = "odom", "base"
        base.transform.translation.x = (now.nanoseconds - t0) / 1e9
        moving.sendTransform(base)

    node.create_timer(0.02, tick)
    try:  # Ctrl-C ends it (KeyboardInterrupt, as rclpy raises it)
        print("static sent", flush=True)
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
