"""The two components of ros2/demos' ``composition`` package, as launchkit Python nodes."""

from __future__ import annotations

from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs.std_msgs.msg import String


class Talker(ros.Node):
    """Publishes ``Hello World: N`` on ``chatter`` every second."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__("talker", **kwargs)
        self.count = 0
        self.publisher = self.create_publisher(String, "chatter", 10)
        self.create_timer(1.0, self.tick)

    def tick(self) -> None:
        """Publish the next greeting."""
        self.count += 1
        text = f"Hello World: {self.count}"
        self.get_logger().info(f"Publishing: '{text}'")
        self.publisher.publish(String(data=text))


class Listener(ros.Node):
    """Logs what it hears on ``chatter``."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__("listener", **kwargs)
        self.create_subscription(String, "chatter", self.heard, 10)

    def heard(self, msg: Any) -> None:
        """Log one message."""
        self.get_logger().info(f"I heard: [{msg.data}]")
