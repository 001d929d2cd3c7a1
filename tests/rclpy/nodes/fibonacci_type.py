"""The Fibonacci action the action nodes use: test_msgs' where the ros-jazzy wheels are
installed (the real rclpy has no example_interfaces there; launchkit reads test_msgs from its
interface files), else example_interfaces' (built into launchkit)."""

try:
    from test_msgs.action import Fibonacci
except ImportError:
    from example_interfaces.action import Fibonacci

__all__ = ["Fibonacci"]
