"""Service definitions registered on top of the Jazzy typestore (rosbags ships messages only).

Each entry is ``"pkg/srv/Name": ".srv text"``; the request and response halves are split at ``---``.
"""

from __future__ import annotations

SERVICES: dict[str, str] = {
    "std_srvs/srv/Empty": "---\n",
    "std_srvs/srv/SetBool": "bool data\n---\nbool success\nstring message\n",
    "std_srvs/srv/Trigger": "---\nbool success\nstring message\n",
    "gazebo_msgs/srv/SpawnEntity": (
        "string name\n"
        "string xml\n"
        "string robot_namespace\n"
        "geometry_msgs/Pose initial_pose\n"
        "string reference_frame\n"
        "---\n"
        "bool success\n"
        "string status_message\n"
    ),
    "gazebo_msgs/srv/DeleteEntity": "string name\n---\nbool success\nstring status_message\n",
    "rcl_interfaces/srv/ListParameters": (
        "uint64 DEPTH_RECURSIVE=0\n"
        "string[] prefixes\n"
        "uint64 depth\n"
        "---\n"
        "rcl_interfaces/ListParametersResult result\n"
    ),
    "rcl_interfaces/srv/GetParameters": (
        "string[] names\n---\nrcl_interfaces/ParameterValue[] values\n"
    ),
    "rcl_interfaces/srv/GetParameterTypes": "string[] names\n---\nuint8[] types\n",
    "rcl_interfaces/srv/SetParameters": (
        "rcl_interfaces/Parameter[] parameters\n---\nrcl_interfaces/SetParametersResult[] results\n"
    ),
    "rcl_interfaces/srv/SetParametersAtomically": (
        "rcl_interfaces/Parameter[] parameters\n---\nrcl_interfaces/SetParametersResult result\n"
    ),
    "rcl_interfaces/srv/DescribeParameters": (
        "string[] names\n---\nrcl_interfaces/ParameterDescriptor[] descriptors\n"
    ),
    "nav_msgs/srv/GetMap": "---\nnav_msgs/OccupancyGrid map\n",
    "nav_msgs/srv/GetPlan": (
        "geometry_msgs/PoseStamped start\n"
        "geometry_msgs/PoseStamped goal\n"
        "float32 tolerance\n"
        "---\n"
        "nav_msgs/Path plan\n"
    ),
    "nav_msgs/srv/SetMap": (
        "nav_msgs/OccupancyGrid map\n"
        "geometry_msgs/PoseWithCovarianceStamped initial_pose\n"
        "---\n"
        "bool success\n"
    ),
    "sensor_msgs/srv/SetCameraInfo": (
        "sensor_msgs/CameraInfo camera_info\n---\nbool success\nstring status_message\n"
    ),
}
