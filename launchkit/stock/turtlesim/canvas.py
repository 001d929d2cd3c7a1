"""The pen trails as a picture: what the turtles drew, and what a colour sensor reads.

Jazzy draws the trails into an image of its own, transparent white where nothing is drawn, with
the background colour painted beneath it at every repaint (so a change of the ``background_*``
parameters shows at once, and ``/clear`` only erases the trails). A colour sensor reads this
image, not the background: on a clear canvas it reads white (255, 255, 255).

A stroke is Qt's: a line of the pen's width with square ends (half the width past each end
point), not anti-aliased. Pillow fills the stroke's outline and writes the PNG that the viewer
loads as a snapshot of the trails.
"""

from __future__ import annotations

import io
import math

from PIL import Image, ImageDraw

from launchkit.stock.turtlesim.world import HEIGHT_PX, WIDTH_PX, Stroke

#: What an undrawn pixel holds: white, fully transparent (Jazzy's ``qRgba(255, 255, 255, 0)``).
CLEAR = (255, 255, 255, 0)

Point = tuple[float, float]


def stroke_outline(p0: Point, p1: Point, width: int) -> list[Point]:
    """The four corners of a square-ended stroke of ``width`` pixels from ``p0`` to ``p1``."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    length = math.hypot(dx, dy)
    ux, uy = (dx / length, dy / length) if length > 0 else (1.0, 0.0)
    half = width / 2.0
    ax, ay = ux * half, uy * half  # along the stroke
    nx, ny = -ay, ax  # across it
    return [
        (p0[0] - ax + nx, p0[1] - ay + ny),
        (p1[0] + ax + nx, p1[1] + ay + ny),
        (p1[0] + ax - nx, p1[1] + ay - ny),
        (p0[0] - ax - nx, p0[1] - ay - ny),
    ]


class PathImage:
    """The trails, ``WIDTH_PX`` x ``HEIGHT_PX`` pixels, RGBA."""

    def __init__(self, width: int = WIDTH_PX, height: int = HEIGHT_PX) -> None:
        self.width = width
        self.height = height
        self.image = Image.new("RGBA", (width, height), CLEAR)
        self._draw = ImageDraw.Draw(self.image)

    def clear(self) -> None:
        """Erase every trail."""
        self.image.paste(CLEAR, (0, 0, self.width, self.height))

    def stroke(self, stroke: Stroke) -> None:
        """Draw a pen stroke."""
        pen = stroke.pen
        outline = stroke_outline(stroke.start, stroke.end, pen.width)
        self._draw.polygon(outline, fill=(pen.r, pen.g, pen.b, 255))

    def color_at(self, x: int, y: int) -> tuple[int, int, int]:
        """The red, green and blue of the pixel at ``(x, y)`` (kept inside the image)."""
        x = min(max(x, 0), self.width - 1)
        y = min(max(y, 0), self.height - 1)
        r, g, b, _ = self.image.getpixel((x, y))  # type: ignore[misc]
        return (int(r), int(g), int(b))

    def png(self) -> bytes:
        """The picture as PNG (fast compression: it is sent, not stored)."""
        out = io.BytesIO()
        self.image.save(out, "PNG", compress_level=1)
        return out.getvalue()
