"""Stand-ins for ROS packages, one subpackage each (executables and share files)."""
