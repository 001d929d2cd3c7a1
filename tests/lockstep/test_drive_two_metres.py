"""The docs' example (docs/testing.md): drive the seed robot 2 m in simulated time."""

import math

from launchkit.ros.msgs.geometry_msgs.msg import Twist
from launchkit.ros.msgs.nav_msgs.msg import Odometry


def test_the_robot_drives_two_metres_in_simulated_time(launch):
    robot = launch(
        "robot_wheel",
        "gazebo_and_rviz.launch.xml",
        args={"start_rviz": False},
        lockstep=True,
        ready_timeout=60,
    )
    robot.subscribe("/odom", Odometry)
    robot.advance(0.5)  # the robot is spawned and settles
    start = robot.latest("/odom").pose.pose.position

    forward = Twist()
    forward.linear.x = 0.5  # the seed's wheels drive it toward its -x at +0.5 (as in Gazebo)
    robot.publish("/cmd_vel", forward)

    def travelled() -> float:
        p = robot.latest("/odom").pose.pose.position
        return math.hypot(p.x - start.x, p.y - start.y)

    robot.wait_until(lambda: travelled() >= 2.0, within=8.0)
    robot.publish("/cmd_vel", Twist())
    robot.advance(1.0)

    end = robot.latest("/odom").pose.pose.position
    assert 2.0 <= math.hypot(end.x - start.x, end.y - start.y) < 2.3
    assert abs(end.y - start.y) < 0.05  # straight ahead
    assert end.x < start.x  # toward the base's -x


def test_the_docs_show_this_file():
    """docs/testing.md's lockstep example is this file, from ``import math`` to the
    line above this test."""
    from tests.support import assert_docs_show

    assert_docs_show(__file__, "import math", "testing.md")
