"""What a node logs reaches /rosout (rcl_interfaces/msg/Log), seen by another node."""

import rclpy
from rcl_interfaces.msg import Log
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node


def main() -> None:
    rclpy.init()
    reader = Node("reader")
    seen = []

    def on_log(msg: Log) -> None:
        if msg.name.startswith("speaker"):
            seen.append(msg)

    reader.create_subscription(Log, "/rosout", on_log, 10)
    speaker = Node("speaker")
    executor = SingleThreadedExecutor()
    executor.add_node(reader)
    executor.add_node(speaker)
    while len(reader.get_publishers_info_by_topic("/rosout")) < 2:  # its own, the speaker's
        executor.spin_once(timeout_sec=0.1)
    info = sorted(i.node_name for i in reader.get_publishers_info_by_topic("/rosout"))
    print("rosout publishers:", info)
    qos = reader.get_publishers_info_by_topic("/rosout")[0].qos_profile
    print("rosout qos:", qos.durability.name, qos.reliability.name)  # DDS tells no depth
    logger = speaker.get_logger()
    logger.set_level(rclpy.logging.LoggingSeverity.DEBUG)
    logger.debug("a debug line")
    logger.info("hello rosout")
    logger.warning("a warning")
    logger.error("an error")
    logger.get_child("part").info("from a child logger")
    while len(seen) < 5:  # the test bounds how long
        executor.spin_once(timeout_sec=0.1)
    for msg in seen:
        print(
            "rosout:",
            msg.level,
            msg.name,
            repr(msg.msg),
            msg.function,
            msg.file.endswith("rosout.py"),
        )
    executor.shutdown()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
