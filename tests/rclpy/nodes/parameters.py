"""Parameters with descriptors and callbacks, and the /parameter_events they publish (seen by
a second node of the same process)."""

import rclpy
from rcl_interfaces.msg import (
    FloatingPointRange,
    IntegerRange,
    ParameterDescriptor,
    ParameterEvent,
    SetParametersResult,
)
from rclpy.exceptions import (
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterNotDeclaredException,
)
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter, parameter_value_to_python


def main() -> None:
    rclpy.init()
    node = Node("configured", parameter_overrides=[Parameter("speed", value=3)])
    watcher = Node("watcher")
    events = []

    def on_event(event) -> None:
        if event.node != "/configured":
            return
        for kind in ("new_parameters", "changed_parameters", "deleted_parameters"):
            for p in getattr(event, kind):
                events.append(f"{kind} {p.name}={parameter_value_to_python(p.value)!r}")

    watcher.create_subscription(ParameterEvent, "/parameter_events", on_event, 10)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.add_node(watcher)
    while node.count_subscribers("/parameter_events") < 1:
        executor.spin_once(timeout_sec=0.1)

    speed = node.declare_parameter(
        "speed",
        1,
        ParameterDescriptor(
            description="wheel speed",
            integer_range=[IntegerRange(from_value=0, to_value=10, step=1)],
        ),
    )
    print("speed (an override):", speed.value)
    node.declare_parameter(
        "gain",
        0.5,
        ParameterDescriptor(
            floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0)]
        ),
    )
    node.declare_parameter("frame", "base", ParameterDescriptor(read_only=True))
    node.declare_parameter("anything", 1, ParameterDescriptor(dynamic_typing=True))
    for attempt in (
        lambda: node.declare_parameter("speed", 2),
        lambda: node.declare_parameter("gain2", 1.0),
        lambda: node.get_parameter("missing"),
    ):
        try:
            attempt()
            print("no error")
        except (ParameterAlreadyDeclaredException, ParameterNotDeclaredException) as exc:
            print(type(exc).__name__ + ":", exc)
    try:
        node.declare_parameter(
            "ratio",
            2,
            ParameterDescriptor(
                floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0)]
            ),
        )
    except InvalidParameterTypeException as exc:
        print("InvalidParameterTypeException:", exc)
    try:
        node.declare_parameter(
            "level",
            20,
            ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=10, step=1)]),
        )
    except InvalidParameterValueException as exc:
        print("InvalidParameterValueException:", exc)

    seen = []

    def on_set(params):
        seen.append(",".join(p.name for p in params))
        if any(p.name == "speed" and p.value == 7 for p in params):
            return SetParametersResult(successful=False, reason="seven is unlucky")
        return SetParametersResult(successful=True)

    def pre_set(params):
        return [*params, Parameter("gain", value=0.25)] if params[0].name == "speed" else params

    node.add_on_set_parameters_callback(on_set)
    node.add_pre_set_parameters_callback(pre_set)
    node.add_post_set_parameters_callback(lambda params: seen.append("post " + params[0].name))
    cases = [
        Parameter("speed", value=5),
        Parameter("speed", value=7),
        Parameter("speed", value=11),
        Parameter("speed", value=2.0),
        Parameter("gain", value=1.5),
        Parameter("frame", value="odom"),
        Parameter("anything", value="now a string"),
    ]
    for result in node.set_parameters(cases):
        print("set:", result.successful, repr(result.reason))
    try:
        node.set_parameters([Parameter("undeclared", value=1)])
    except ParameterNotDeclaredException as exc:
        print("ParameterNotDeclaredException:", exc)
    print("callbacks saw:", seen)
    print(
        "speed now:",
        node.get_parameter("speed").value,
        "gain now:",
        node.get_parameter("gain").value,
    )
    print("describe speed:", node.describe_parameter("speed").description)
    node.undeclare_parameter("anything")
    expected = 8  # 5 declared, then speed and gain set together, then anything
    while len(events) < expected:  # the test bounds how long
        executor.spin_once(timeout_sec=0.1)
    for line in events:
        print("event:", line)
    executor.shutdown()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
