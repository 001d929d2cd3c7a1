"""The picture of a turtlesim for the browser viewer: two hidden, latched topics of JSON text.

turtlesim_node publishes them as ``std_msgs/String`` on ``/_turtlesim<node>/scene`` and
``/_turtlesim<node>/trails`` (``/_turtlesim/turtlesim/scene`` for the node ``/turtlesim``);
hidden names, so ``topic list`` leaves them out, and transient local with depth 1, so a page
that opens later gets the picture at once. The viewer page (``web/js/turtlesim.js``) draws them.

``trails`` is a snapshot of the pen trails, published when they were cleared and then at most
every :data:`SNAPSHOT_PERIOD_S` while they grow (or after :data:`SNAPSHOT_STROKES` strokes)::

    {"session": "3f2a...", "serial": 7, "upto": 412, "png": "<base64 PNG>" | null}

``serial`` numbers the snapshots; ``upto`` counts the strokes the snapshot holds, of all
strokes ever drawn by this node; ``png`` is ``null`` when nothing is drawn. ``scene`` is
everything else, published at the update rate while anything changes::

    {"session": ..., "size": [500, 500], "meter": 45.0, "background": [69, 86, 255],
     "turtles": [{"name": "turtle1", "x": 5.5444, "y": 5.5444, "theta": 0.0, "image": 3}],
     "base": 412, "upto": 430, "strokes": [[x0, y0, x1, y1, r, g, b, width], ...]}

``strokes`` are the strokes drawn since the latest snapshot (numbers ``base`` to ``upto``), in
pixels with y down. A page draws a snapshot's PNG, then the strokes it does not have yet, and
is complete whichever of the two topics it hears first. ``session`` changes when the node
restarts (its counts start again).
"""

from __future__ import annotations

import base64
import json
import uuid
from collections.abc import Iterable
from typing import Any

from launchkit.stock.turtlesim.canvas import PathImage
from launchkit.stock.turtlesim.world import HEIGHT_PX, METER_PX, WIDTH_PX, Stroke, Turtle

#: The hidden namespace of the picture's topics.
PREFIX = "/_turtlesim"
#: A snapshot of growing trails at most this often ...
SNAPSHOT_PERIOD_S = 2.0
#: ... or after this many strokes, which also bounds a scene message.
SNAPSHOT_STROKES = 300


def topics(node_fqn: str) -> tuple[str, str]:
    """The scene and trails topics of the node ``node_fqn`` (``/turtlesim``)."""
    base = PREFIX + (node_fqn if node_fqn.startswith("/") else "/" + node_fqn)
    return (base + "/scene", base + "/trails")


def _round(value: float, digits: int) -> float:
    return round(float(value), digits)


class SceneFeed:
    """The trails (drawn into a :class:`PathImage`), their strokes since the last snapshot,
    and the messages of the two topics."""

    def __init__(self, path: PathImage) -> None:
        self.path = path
        self.session = uuid.uuid4().hex[:12]
        self._count = 0
        self._base = 0
        self._strokes: list[list[float]] = []
        self._empty = True
        self._snapshot_due = True
        self._serial = 0
        self._last_snapshot_s = float("-inf")
        self._last_scene: str | None = None

    def stroke(self, stroke: Stroke) -> None:
        """Draw ``stroke`` into the trails and remember it for the next scene."""
        self.path.stroke(stroke)
        pen = stroke.pen
        (x0, y0), (x1, y1) = stroke.start, stroke.end
        points = [_round(x0, 2), _round(y0, 2), _round(x1, 2), _round(y1, 2)]
        self._strokes.append([*points, pen.r, pen.g, pen.b, pen.width])
        self._count += 1
        self._empty = False

    def clear(self) -> None:
        """Erase the trails; the next snapshot says so."""
        self.path.clear()
        self._base = self._count
        self._strokes = []
        self._empty = True
        self._snapshot_due = True

    def snapshot(self, now_s: float) -> str | None:
        """The ``trails`` message, when one is due now; else None."""
        growing = bool(self._strokes) and (
            len(self._strokes) >= SNAPSHOT_STROKES
            or now_s - self._last_snapshot_s >= SNAPSHOT_PERIOD_S
        )
        if not (self._snapshot_due or growing):
            return None
        self._snapshot_due = False
        self._serial += 1
        self._last_snapshot_s = now_s
        self._base = self._count
        self._strokes = []
        png = None if self._empty else base64.b64encode(self.path.png()).decode("ascii")
        body = {"session": self.session, "serial": self._serial, "upto": self._base, "png": png}
        return json.dumps(body)

    def scene(self, background: tuple[int, int, int], turtles: Iterable[Turtle]) -> str | None:
        """The ``scene`` message, when it differs from the last one given; else None."""
        body: dict[str, Any] = {
            "session": self.session,
            "size": [WIDTH_PX, HEIGHT_PX],
            "meter": METER_PX,
            "background": list(background),
            "turtles": [
                {
                    "name": t.name,
                    "x": _round(t.x, 4),
                    "y": _round(t.y, 4),
                    "theta": _round(t.orient, 4),
                    "image": t.image,
                }
                for t in turtles
            ],
            "base": self._base,
            "upto": self._count,
            "strokes": self._strokes,
        }
        text = json.dumps(body, separators=(",", ":"))
        if text == self._last_scene:
            return None
        self._last_scene = text
        return text
