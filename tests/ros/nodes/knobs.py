"""Test node for the parameter and service commands: ``/knobs`` with parameters of every kind,
a ``~/toggle`` service (std_srvs/srv/SetBool), and one rcl_interfaces/msg/Log on ``/rosout`` with
fixed values (reliable, transient local, depth 1000: rcl's QoS for ``/rosout``)."""

from launchkit.ros.msgs.builtin_interfaces.msg import Time
from launchkit.ros.msgs.rcl_interfaces.msg import Log
from launchkit.ros.msgs.std_srvs.srv import SetBool

import launchkit.ros as ros


def main() -> None:
    ros.init()
    node = ros.Node("knobs")
    for name, value in (
        ("count", 5),
        ("rate", 2.5),
        ("label", "hi there"),
        ("enabled", True),
        ("ids", [1, 2, 3]),
        ("gains", [0.5, 1.5]),
        ("names", ["a", "b"]),
        ("flags", [True, False]),
        ("nested.depth", 3),
    ):
        node.declare_parameter(name, value)

    def toggle(request: SetBool.Request, response: SetBool.Response) -> SetBool.Response:
        response.success = True
        response.message = f"toggled to {request.data}"
        return response

    node.create_service(SetBool, "~/toggle", toggle)
    qos = ros.QoSProfile(depth=1000, durability=ros.DurabilityPolicy.TRANSIENT_LOCAL)
    rosout = node.create_publisher(Log, "/rosout", qos)
    rosout.publish(
        Log(
            stamp=Time(sec=1700000000, nanosec=5),
            level=20,
            name="cli_test_log",
            msg="hello from knobs",
            file="knobs.py",
            function="main",
            line=42,
        )
    )
    print("knobs ready", flush=True)
    ros.spin(node)
    node.destroy_node()
    ros.shutdown()


if __name__ == "__main__":
    main()
