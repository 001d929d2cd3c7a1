"""The ``tf2_echo`` executable: print the transform between two frames, as tf2_ros' does.

``ros2 run tf2_ros tf2_echo SOURCE TARGET [RATE]`` prints, ``RATE`` times a second (default 1),
the latest transform that takes data in ``TARGET`` into ``SOURCE``: translation, rotation as a
quaternion and as roll, pitch, yaw, and the 4x4 matrix. Until the frames connect it says what it
waits for, at most once a second.
"""

from __future__ import annotations

import math
import sys
import threading
from typing import Any

import launchkit.ros as ros
from launchkit.errors import UserError
from launchkit.ros.arguments import remove_ros_args
from launchkit.ros.tf2 import Buffer, TransformException, TransformListener
from launchkit.ros.tf2.rotation import to_matrix
from launchkit.rotations import quaternion_to_rpy
from launchkit.stock import _entry

USAGE = "tf2_echo source_frame target_frame [echo_rate]"


def rate_of(text: str) -> float:
    """The echo rate argument (a whole number, as tf2_echo reads it)."""
    try:
        return float(text)
    except ValueError:
        raise UserError(
            f"Failed to convert rate argument '{text}' to a floating-point number",
            expected="a rate in Hz, e.g. 10",
        ) from None


def report(transform: Any) -> str:
    """The lines tf2_echo prints for one transform."""
    stamp = transform.header.stamp
    t, r = transform.transform.translation, transform.transform.rotation
    quaternion = (r.x, r.y, r.z, r.w)
    roll, pitch, yaw = quaternion_to_rpy(quaternion)
    matrix = to_matrix(quaternion)
    lines = [
        f"At time {stamp.sec}.{stamp.nanosec}",
        f"- Translation: [{t.x:.3f}, {t.y:.3f}, {t.z:.3f}]",
        f"- Rotation: in Quaternion [{r.x:.3f}, {r.y:.3f}, {r.z:.3f}, {r.w:.3f}]",
        f"- Rotation: in RPY (radian) [{roll:.3f}, {pitch:.3f}, {yaw:.3f}]",
        "- Rotation: in RPY (degree) ["
        f"{math.degrees(roll):.3f}, {math.degrees(pitch):.3f}, {math.degrees(yaw):.3f}]",
        "- Matrix:",
    ]
    for row, offset in zip(matrix, (t.x, t.y, t.z), strict=True):
        lines.append("".join(f" {value:6.3f}" for value in (*row, offset)))
    lines.append("".join(f" {value:6.3f}" for value in (0.0, 0.0, 0.0, 1.0)))
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    """Echo the transform until Ctrl-C."""
    args = remove_ros_args(argv)[1:]
    if len(args) not in (2, 3):
        raise UserError(f"{len(args)} argument(s) given", expected=USAGE)
    source, target = args[0], args[1]
    period = 1.0 / rate_of(args[2]) if len(args) == 3 else 1.0
    with _entry.ros_node(argv, "tf2_echo") as node:
        stopped = threading.Event()  # Ctrl-C shuts the context down: stop sleeping at once
        ros.default_context.on_shutdown(stopped.set)
        buffer = Buffer()
        listener = TransformListener(buffer, node, spin_thread=True)
        try:
            while ros.ok():
                ready, why = buffer.can_transform(
                    source, target, ros.Time(), return_debug_tuple=True
                )
                if ready:
                    break
                node.get_logger().info(
                    f"Waiting for transform {source} ->  {target}: {why}", throttle_duration_sec=1.0
                )
                stopped.wait(period)
            while ros.ok():
                try:
                    print(report(buffer.lookup_transform(source, target, ros.Time())), flush=True)
                except TransformException as error:
                    print(
                        f"Failure at {node.get_clock().now().nanoseconds / 1e9}\n"
                        f"Exception thrown:{error}\n"
                        f"The current list of frames is:\n{buffer.all_frames_as_string()}",
                        flush=True,
                    )
                stopped.wait(period)
        finally:
            del listener  # stops its spinning thread
    return 0


if __name__ == "__main__":
    sys.exit(_entry.run(main, "tf2_echo"))
