"""Run on the viewer's host: fetch the viewer page and, over its Foxglove WebSocket, wait for
the robot's description and transforms; print what arrived (for test_robot_two_hosts)."""

from __future__ import annotations

import sys
import urllib.request
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "stock"))
from foxglove_client import receive_topics

from launchkit.ros.msgs import deserialize


def main(port: int) -> None:
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=20) as page:
        print(f"page: {page.status} {len(page.read())} bytes", flush=True)
    client = receive_topics(f"ws://127.0.0.1:{port}", ["/robot_description", "/tf"], 60)
    description = deserialize(client.received["/robot_description"][0], "std_msgs/msg/String")
    frames = {
        t.child_frame_id
        for raw in client.received["/tf"]
        for t in deserialize(raw, "tf2_msgs/msg/TFMessage").transforms
    }
    print(f"robot: {'three_wheeled_robot' in description.data}", flush=True)
    print(f"frames: {' '.join(sorted(frames))}", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]))
