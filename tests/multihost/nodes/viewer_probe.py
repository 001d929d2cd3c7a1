"""Run on the viewer's host: fetch the viewer page and, over its Foxglove WebSocket, wait for
the robot's description and transforms; print what arrived (for test_robot_two_hosts)."""

from __future__ import annotations

import asyncio
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "stock"))
from foxglove_client import FoxgloveClient

from launchkit.ros.msgs import deserialize

TOPICS = ["/robot_description", "/tf"]


def _frames(client: FoxgloveClient) -> set[str]:
    return {
        t.child_frame_id
        for raw in client.received.get("/tf", [])
        for t in deserialize(raw, "tf2_msgs/msg/TFMessage").transforms
    }


async def _receive(url: str, timeout: float) -> FoxgloveClient:
    # /tf has two publishers (the state publisher's joints, the diff drive's odom -> base):
    # wait for both, whichever starts first
    async with FoxgloveClient(url) as client:
        await client.wait_for(
            f"rviz2 to advertise {TOPICS}",
            lambda: all(t in client.channels for t in TOPICS),
            timeout,
        )
        await client.subscribe(TOPICS)
        await client.wait_for(
            "the description and the base frame",
            lambda: "/robot_description" in client.received and "base" in _frames(client),
            timeout,
        )
        return client


def _page(url: str, timeout: float) -> tuple[int, int]:
    """The page's status and size; the agent says it started rviz2 before rviz2 listens, so a
    refused connection is tried again until ``timeout``."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            with urllib.request.urlopen(url, timeout=20) as page:
                return page.status, len(page.read())
        except urllib.error.URLError as error:
            if not isinstance(error.reason, ConnectionRefusedError):
                raise
            if time.monotonic() > deadline:
                raise
        time.sleep(0.2)


def main(port: int) -> None:
    status, size = _page(f"http://127.0.0.1:{port}/", 60)
    print(f"page: {status} {size} bytes", flush=True)
    client = asyncio.run(_receive(f"ws://127.0.0.1:{port}", 60))
    description = deserialize(client.received["/robot_description"][0], "std_msgs/msg/String")
    print(f"robot: {'three_wheeled_robot' in description.data}", flush=True)
    print(f"frames: {' '.join(sorted(_frames(client)))}", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]))
