"""Conversions from the simulation core's plain values to ROS messages (launchkit.ros types).

Numeric sequences are given as ``array.array`` or ``bytes`` (what the message classes hold, as
rclpy's do: no conversion element by element), fixed-size arrays as lists.
"""

from __future__ import annotations

import array
from typing import TYPE_CHECKING, Any

from launchkit.ros.msgs import get_message, get_service

if TYPE_CHECKING:  # the simulation core (numpy) is not for spawn_entity, which uses this too
    from launchkit.stock.gazebo_ros.sim.diff_drive import Odometry
    from launchkit.stock.gazebo_ros.sim.sensors import CameraConfig, LidarConfig


def message_class(package: str, name: str) -> Any:
    """Message class ``package/msg/name`` of the ROS layer: the one way the simulator's nodes
    get their message types."""
    return get_message(f"{package}/msg/{name}")


def service_class(package: str, name: str) -> Any:
    """Service type ``package/srv/name`` of the ROS layer."""
    return get_service(f"{package}/srv/{name}")


def point(cls: Any, xyz: Any) -> Any:
    """A ``Point`` or ``Vector3`` (``cls``) from three numbers (message classes take keywords
    only, as rclpy's)."""
    x, y, z = xyz
    return cls(x=float(x), y=float(y), z=float(z))


def quaternion(cls: Any, xyzw: Any) -> Any:
    """A ``Quaternion`` (``cls``) from four numbers."""
    x, y, z, w = xyzw
    return cls(x=float(x), y=float(y), z=float(z), w=float(w))


#: Topics between the simulator and the diff drive node process, per entity.
STATE_TOPIC = "/gazebo/{entity}/joint_states"
GROUND_TRUTH_TOPIC = "/gazebo/{entity}/ground_truth"
COMMAND_TOPIC = "/gazebo/{entity}/joint_commands"


def stamp(seconds: float) -> Any:
    """A ``builtin_interfaces/Time`` for ``seconds`` of sim time."""
    Time = message_class("builtin_interfaces", "Time")

    nanoseconds = round(seconds * 1e9)
    return Time(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def seconds_of(time_msg: Any) -> float:
    """Seconds of a ``builtin_interfaces/Time``."""
    return float(time_msg.sec) + float(time_msg.nanosec) * 1e-9


def header(seconds: float, frame_id: str) -> Any:
    """A ``std_msgs/Header``."""
    Header = message_class("std_msgs", "Header")

    return Header(stamp=stamp(seconds), frame_id=frame_id)


def clock(seconds: float) -> Any:
    """A ``rosgraph_msgs/Clock``."""
    Clock = message_class("rosgraph_msgs", "Clock")

    return Clock(clock=stamp(seconds))


def odometry(odom: Odometry) -> Any:
    """A ``nav_msgs/Odometry`` from the diff drive's odometry."""
    Point = message_class("geometry_msgs", "Point")
    Pose = message_class("geometry_msgs", "Pose")
    PoseWithCovariance = message_class("geometry_msgs", "PoseWithCovariance")
    Quaternion = message_class("geometry_msgs", "Quaternion")
    Twist = message_class("geometry_msgs", "Twist")
    TwistWithCovariance = message_class("geometry_msgs", "TwistWithCovariance")
    Vector3 = message_class("geometry_msgs", "Vector3")
    OdometryMsg = message_class("nav_msgs", "Odometry")

    return OdometryMsg(
        header=header(odom.stamp, odom.frame_id),
        child_frame_id=odom.child_frame_id,
        pose=PoseWithCovariance(
            pose=Pose(
                position=point(Point, odom.position),
                orientation=quaternion(Quaternion, odom.orientation),
            ),
            covariance=list(odom.pose_covariance),
        ),
        twist=TwistWithCovariance(
            twist=Twist(linear=point(Vector3, odom.linear), angular=point(Vector3, odom.angular)),
            covariance=list(odom.twist_covariance),
        ),
    )


def transform(odom: Odometry) -> Any:
    """A ``tf2_msgs/TFMessage`` with the odometry's ``frame_id -> child_frame_id`` transform."""
    Quaternion = message_class("geometry_msgs", "Quaternion")
    Transform = message_class("geometry_msgs", "Transform")
    TransformStamped = message_class("geometry_msgs", "TransformStamped")
    Vector3 = message_class("geometry_msgs", "Vector3")
    TFMessage = message_class("tf2_msgs", "TFMessage")

    return TFMessage(
        transforms=[
            TransformStamped(
                header=header(odom.stamp, odom.frame_id),
                child_frame_id=odom.child_frame_id,
                transform=Transform(
                    translation=point(Vector3, odom.position),
                    rotation=quaternion(Quaternion, odom.orientation),
                ),
            )
        ]
    )


def laser_scan(config: LidarConfig, seconds: float, ranges: list[float]) -> Any:
    """A ``sensor_msgs/LaserScan`` as gazebo_ros_ray_sensor fills it."""
    LaserScan = message_class("sensor_msgs", "LaserScan")

    return LaserScan(
        header=header(seconds, config.frame_id),
        angle_min=config.min_angle,
        angle_max=config.max_angle,
        angle_increment=config.angle_increment,
        time_increment=0.0,
        scan_time=0.0,
        range_min=config.range_min,
        range_max=config.range_max,
        ranges=array.array("f", ranges),
        intensities=array.array("f", [0.0]) * len(ranges),
    )


def image(config: CameraConfig, seconds: float, data: bytes) -> Any:
    """A ``sensor_msgs/Image`` of one rendered frame."""
    Image = message_class("sensor_msgs", "Image")

    return Image(
        header=header(seconds, config.frame_id),
        height=config.height,
        width=config.width,
        encoding=config.encoding,
        is_bigendian=0,
        step=config.width * config.channels,
        data=data,  # bytes: one copy into the message's array.array
    )


def camera_info(config: CameraConfig, seconds: float) -> Any:
    """A ``sensor_msgs/CameraInfo`` as gazebo_ros_camera fills it (plumb_bob, no distortion)."""
    CameraInfo = message_class("sensor_msgs", "CameraInfo")

    k, p = config.intrinsics()
    return CameraInfo(
        header=header(seconds, config.frame_id),
        height=config.height,
        width=config.width,
        distortion_model="plumb_bob",
        d=array.array("d", [0.0] * 5),
        k=list(k),
        r=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        p=list(p),
    )


def joint_state(
    seconds: float,
    names: list[str],
    positions: list[float],
    velocities: list[float],
    efforts: list[float],
) -> Any:
    """A ``sensor_msgs/JointState``."""
    JointState = message_class("sensor_msgs", "JointState")

    return JointState(
        header=header(seconds, ""),
        name=list(names),
        position=array.array("d", positions),
        velocity=array.array("d", velocities),
        effort=array.array("d", efforts),
    )
