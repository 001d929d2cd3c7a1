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
    "rcl_interfaces/srv/GetLoggerLevels": (
        "string[] names\n---\nrcl_interfaces/LoggerLevel[] levels\n"
    ),
    "rcl_interfaces/srv/SetLoggerLevels": (
        "rcl_interfaces/LoggerLevel[] levels\n---\nrcl_interfaces/SetLoggerLevelsResult[] results\n"
    ),
    # the ROS 2 examples' and tutorials' service (example_interfaces has no wheel to check
    # against; its definition is upstream's)
    "example_interfaces/srv/AddTwoInts": "int64 a\nint64 b\n---\nint64 sum\n",
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
    "lifecycle_msgs/srv/ChangeState": "lifecycle_msgs/Transition transition\n---\nbool success\n",
    "lifecycle_msgs/srv/GetState": "---\nlifecycle_msgs/State current_state\n",
    "lifecycle_msgs/srv/GetAvailableStates": "---\nlifecycle_msgs/State[] available_states\n",
    "lifecycle_msgs/srv/GetAvailableTransitions": (
        "---\nlifecycle_msgs/TransitionDescription[] available_transitions\n"
    ),
    # composition_interfaces has no wheel to check against; field names as upstream, including
    # its "error_messsage" (three s), which the type hash depends on.
    "composition_interfaces/srv/LoadNode": (
        "string package_name\n"
        "string plugin_name\n"
        "string node_name\n"
        "string node_namespace\n"
        "uint8 log_level\n"
        "string[] remap_rules\n"
        "rcl_interfaces/Parameter[] parameters\n"
        "rcl_interfaces/Parameter[] extra_arguments\n"
        "---\n"
        "bool success\n"
        "string error_messsage\n"
        "string full_node_name\n"
        "uint64 unique_id\n"
    ),
    "composition_interfaces/srv/UnloadNode": (
        "uint64 unique_id\n---\nbool success\nstring error_messsage\n"
    ),
    "composition_interfaces/srv/ListNodes": "---\nstring[] full_node_names\nuint64[] unique_ids\n",
}
