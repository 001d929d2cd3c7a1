"""``rclpy.parameter``: parameters and their messages."""

from launchkit.ros.params import (
    PARAMETER_SEPARATOR_STRING,
    Parameter,
    get_parameter_value,
    parameter_dict_from_yaml_file,
    parameter_value_to_python,
)

__all__ = [
    "PARAMETER_SEPARATOR_STRING",
    "Parameter",
    "get_parameter_value",
    "parameter_dict_from_yaml_file",
    "parameter_value_to_python",
]
