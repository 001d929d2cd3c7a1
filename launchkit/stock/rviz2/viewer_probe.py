"""Whether a launchkit viewer answers on a port: the rviz2 stand-in's server (run by rviz2, or
by turtlesim_node for its own picture) greets a page's WebSocket with a ``hello``.

turtlesim_node asks this when its port is taken, to say that the viewer there shows it too;
rviz2 asks it to take a free port instead of failing, since another viewer holding the default
port is the usual case when turtlesim and a launch with rviz2 run side by side.
"""

from __future__ import annotations

import contextlib
import json

from launchkit.stock.rviz2.page_session import SUBPROTOCOL

#: Seconds to wait for a busy port's server to greet as a launchkit viewer.
PROBE_TIMEOUT = 2.0


def is_viewer(address: str, port: int) -> bool:
    """Whether a launchkit viewer answers at ``address:port`` (``0.0.0.0``: on loopback)."""
    from websockets.sync.client import connect
    from websockets.typing import Subprotocol

    host = "127.0.0.1" if address in ("", "0.0.0.0") else address
    host = f"[{host}]" if ":" in host else host
    url = f"ws://{host}:{port}/"
    with contextlib.suppress(Exception):  # anything but a viewer's greeting means no
        with connect(
            url, subprotocols=[Subprotocol(SUBPROTOCOL)], open_timeout=PROBE_TIMEOUT
        ) as ws:
            greeting = json.loads(ws.recv(timeout=PROBE_TIMEOUT))
            return isinstance(greeting, dict) and greeting.get("op") == "hello"
    return False
