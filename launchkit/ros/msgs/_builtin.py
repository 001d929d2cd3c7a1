"""What launchkit adds to rosbags' ROS 2 Jazzy message definitions to make its built-in store.

``INTERFACES``: ``"pkg/kind/Name": "file text"``, read as an interface file is (comments left
out): the services of the ros-jazzy wheels' interface packages (rosbags ships messages only),
those launchkit's nodes serve, and ``example_interfaces`` (which ROS 2's examples use and no
wheel ships; its ``WString`` is left out, wide strings being unsupported). ``DEFAULTS``: the
default values the Jazzy ``.msg`` files write, which rosbags' store does not keep (rclpy's
classes have them: ``Quaternion().w == 1.0``).
"""

from __future__ import annotations

from typing import Any

DEFAULTS: dict[str, dict[str, Any]] = {
    "geometry_msgs/msg/Quaternion": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0},
    "rcl_interfaces/msg/ParameterDescriptor": {"read_only": False, "dynamic_typing": False},
    "sensor_msgs/msg/NavSatStatus": {"status": -2},
    "type_description_interfaces/msg/FieldType": {"type_id": 0},
}

_SERVICES: dict[str, str] = {
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
    # the tf2_frames service of a tf2_ros Buffer made with a node
    "tf2_msgs/srv/FrameGraph": "---\nstring frame_yaml\n",
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
    "action_msgs/srv/CancelGoal": (
        "GoalInfo goal_info\n"
        "---\n"
        "int8 ERROR_NONE=0\n"
        "int8 ERROR_REJECTED=1\n"
        "int8 ERROR_UNKNOWN_GOAL_ID=2\n"
        "int8 ERROR_GOAL_TERMINATED=3\n"
        "int8 return_code\n"
        "GoalInfo[] goals_canceling\n"
    ),
    "diagnostic_msgs/srv/AddDiagnostics": (
        "string load_namespace\n---\nbool success\nstring message\n"
    ),
    "diagnostic_msgs/srv/SelfTest": "---\nstring id\nbyte passed\nDiagnosticStatus[] status\n",
    "nav_msgs/srv/LoadMap": (
        "string map_url\n"
        "---\n"
        "uint8 RESULT_SUCCESS=0\n"
        "uint8 RESULT_MAP_DOES_NOT_EXIST=1\n"
        "uint8 RESULT_INVALID_MAP_DATA=2\n"
        "uint8 RESULT_INVALID_MAP_METADATA=3\n"
        "uint8 RESULT_UNDEFINED_FAILURE=255\n"
        "nav_msgs/OccupancyGrid map\n"
        "uint8 result\n"
    ),
    "rcl_interfaces/srv/GetLoggerLevels": "string[] names\n---\nLoggerLevel[] levels\n",
    "rcl_interfaces/srv/SetLoggerLevels": (
        "LoggerLevel[] levels\n---\nSetLoggerLevelsResult[] results\n"
    ),
    "type_description_interfaces/srv/GetTypeDescription": (
        "string type_name\n"
        "string type_hash\n"
        "bool include_type_sources true\n"
        "---\n"
        "bool successful\n"
        "string failure_reason\n"
        "TypeDescription type_description\n"
        "TypeSource[] type_sources\n"
        "KeyValue[] extra_information\n"
    ),
    "visualization_msgs/srv/GetInteractiveMarkers": (
        "---\nuint64 sequence_number\nInteractiveMarker[] markers\n"
    ),
}

_NUMBERS = ("Int8", "Int16", "Int32", "Int64", "UInt8", "UInt16", "UInt32", "UInt64")
_EXAMPLE_SCALARS = {
    "Bool": "bool",
    "Byte": "byte",
    "Char": "char",
    "Float32": "float32",
    "Float64": "float64",
    "String": "string",
    **{name: name.lower() for name in _NUMBERS},
}
_EXAMPLE_ARRAYS = {name: name.lower() for name in ("Byte", "Float32", "Float64", *_NUMBERS)}
_EXAMPLE_INTERFACES: dict[str, str] = {
    "example_interfaces/msg/Empty": "",
    **{f"example_interfaces/msg/{n}": f"{t} data\n" for n, t in _EXAMPLE_SCALARS.items()},
    **{
        f"example_interfaces/msg/{n}MultiArray": f"MultiArrayLayout layout\n{t}[] data\n"
        for n, t in _EXAMPLE_ARRAYS.items()
    },
    "example_interfaces/msg/MultiArrayDimension": "string label\nuint32 size\nuint32 stride\n",
    "example_interfaces/msg/MultiArrayLayout": "MultiArrayDimension[] dim\nuint32 data_offset\n",
    "example_interfaces/srv/AddTwoInts": "int64 a\nint64 b\n---\nint64 sum\n",
    "example_interfaces/srv/SetBool": "bool data\n---\nbool success\nstring message\n",
    "example_interfaces/srv/Trigger": "---\nbool success\nstring message\n",
    "example_interfaces/action/Fibonacci": (
        "int32 order\n---\nint32[] sequence\n---\nint32[] sequence\n"
    ),
}

INTERFACES: dict[str, str] = {**_SERVICES, **_EXAMPLE_INTERFACES}
