"""A node written against tf2_ros' API: a buffer and a listener spinning in its own thread,
then lookups from the main thread, each result printed on one line for the test to check."""

from __future__ import annotations

import time
from typing import Any

from tf2_ros import Buffer, LookupException, TransformListener

import launchkit.ros as rclpy
from launchkit.ros.clock import Duration, Time


def line(name: str, transform: Any) -> str:
    stamp = transform.header.stamp
    t = transform.transform.translation
    r = transform.transform.rotation
    return (
        f"{name} {stamp.sec * 1_000_000_000 + stamp.nanosec} "
        f"{t.x!r} {t.y!r} {t.z!r} {r.z!r} {r.w!r}"
    )


def main() -> None:
    rclpy.init()
    node = rclpy.Node("tf_listener")
    buffer = Buffer(node=node)
    TransformListener(buffer, node, spin_thread=True)
    # the latest, once the static laser and the moving base are both there
    print(line("latest", buffer.lookup_transform("odom", "laser", Time(), Duration(seconds=60))))
    # a time the data has not reached yet: waits for it
    ahead = node.get_clock().now() + Duration(seconds=0.3)
    print(line("ahead", buffer.lookup_transform("odom", "base", ahead, Duration(seconds=30))))
    # a time inside the history this wait gave the buffer, between two stamps
    when = buffer.get_latest_common_time("odom", "base") - Duration(seconds=0.105)
    print(line("past", buffer.lookup_transform("odom", "base", when)))
    started = time.monotonic()
    try:
        buffer.lookup_transform("odom", "gripper", Time(), Duration(seconds=0.5))
    except LookupException as error:
        print(f"gave up after {time.monotonic() - started:.3f} s: {error}")
    try:  # waits for Ctrl-C, which ends it (KeyboardInterrupt, as rclpy raises it)
        print("done", flush=True)
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
