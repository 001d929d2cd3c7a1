"""The TF tree as ``view_frames`` draws it: Graphviz dot text (what ``frames_*.gv`` holds), and,
where Graphviz is not installed, an SVG picture of the same tree drawn here.

Both take the frames as tf2's ``all_frames_as_yaml`` describes them: for each child frame its
``parent``, ``broadcaster``, ``rate``, ``buffer_length``, ``most_recent_transform`` and
``oldest_transform``.
"""

from __future__ import annotations

from typing import Any
from xml.sax.saxutils import escape

NO_DATA = "No tf data received"
_QUOTE = {'"': "&quot;"}  # escaped in attributes too

Frames = dict[str, dict[str, Any]]


def _quoted(text: object) -> str:
    return '"' + str(text).replace("\\", "\\\\").replace('"', '\\"') + '"'


def edge_lines(data: dict[str, Any]) -> list[str]:
    """What an arrow of the tree says about its child frame, line by line (view_frames')."""
    return [
        f"Broadcaster: {data['broadcaster']}",
        f"Average rate: {data['rate']}",
        f"Buffer length: {data['buffer_length']}",
        f"Most recent transform: {data['most_recent_transform']}",
        f"Oldest transform: {data['oldest_transform']}",
    ]


def roots(frames: Frames) -> list[str]:
    """The frames that are parents but no frame's child, sorted."""
    return sorted({str(d["parent"]) for d in frames.values()} - set(frames))


def to_dot(frames: Frames, recorded_at: float) -> str:
    """The tree as Graphviz dot: one labelled arrow per frame from its parent, and a legend box
    with the time the tree was recorded, as view_frames writes it."""
    if not frames:
        return f"digraph G {{ {_quoted(NO_DATA)} }}"
    lines = ["digraph G {"]
    for child, data in frames.items():
        label = "".join(line + "\\n" for line in edge_lines(data))
        lines.append(f'{_quoted(data["parent"])} -> {_quoted(child)}[label=" {label}"];')
    lines.append("edge [style=invis];")
    lines.append(' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";')
    lines.append(f"{_quoted(f'Recorded at time: {recorded_at}')}[ shape=plaintext ] ;")
    lines.append(f"}}->{_quoted(roots(frames)[0])};")
    lines.append("}")
    return "\n".join(lines) + "\n"


# the SVG drawing: each frame an ellipse, children in the row below their parent
_CHAR = 7.0  # px a character of the 12 px font takes, about
_ROW = 150.0
_GAP = 30.0
_LINE = 13.0


def _width(frame: str, frames: Frames) -> float:
    """The width a frame's column needs: its name, and the label of the arrow to it."""
    texts = [frame, *(edge_lines(frames[frame]) if frame in frames else [])]
    return max(len(t) for t in texts) * _CHAR + _GAP


def to_svg(frames: Frames, recorded_at: float) -> str:
    """The tree as an SVG picture (what ``launchkit tf view-frames`` writes without Graphviz)."""
    children: dict[str, list[str]] = {}
    for child, data in frames.items():
        children.setdefault(str(data["parent"]), []).append(child)
    place: dict[str, tuple[float, float]] = {}
    right = [20.0]  # the next free x

    def lay(frame: str, depth: int) -> float:
        """Place ``frame``'s subtree from the free x on; the frame's centre x."""
        kids = sorted(children.get(frame, []))
        if kids:
            centres = [lay(kid, depth + 1) for kid in kids]
            x = (centres[0] + centres[-1]) / 2
            right[0] = max(right[0], x + _width(frame, frames) / 2)
        else:
            width = _width(frame, frames)
            x = right[0] + width / 2
            right[0] += width
        place[frame] = (x, 70 + depth * _ROW)
        return x

    for root in roots(frames) or ([NO_DATA] if not frames else []):
        lay(root, 0)
    height = max((y for _, y in place.values()), default=70) + 60
    width = right[0] + 20
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
        f'viewBox="0 0 {width:.0f} {height:.0f}" font-family="sans-serif" font-size="12">',
        '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="8" '
        'markerHeight="8" orient="auto"><path d="M0,0 L10,5 L0,10 z"/></marker></defs>',
        '<rect width="100%" height="100%" fill="white"/>',
        f'<text x="20" y="24" font-weight="bold">view_frames Result</text>'
        f'<text x="20" y="40">Recorded at time: {recorded_at}</text>',
    ]
    for child, data in frames.items():
        (x1, y1), (x2, y2) = place[str(data["parent"])], place[child]
        out.append(
            f'<path d="M{x1:.1f},{y1 + 14:.1f} L{x2:.1f},{y2 - 14:.1f}" stroke="black" '
            'fill="none" marker-end="url(#arrow)"/>'
        )
        top = (y1 + y2) / 2 - 2 * _LINE
        for index, line in enumerate(edge_lines(data)):
            out.append(
                f'<text x="{x2 + 6:.1f}" y="{top + index * _LINE:.1f}" font-size="10">'
                f"{escape(line)}</text>"
            )
    for frame, (x, y) in place.items():
        rx = len(frame) * _CHAR / 2 + 14
        out.append(
            f'<g data-frame="{escape(frame, _QUOTE)}"><ellipse cx="{x:.1f}" cy="{y:.1f}" '
            f'rx="{rx:.1f}" ry="14" fill="white" stroke="black"/><text x="{x:.1f}" y="{y + 4:.1f}" '
            f'text-anchor="middle">{escape(frame)}</text></g>'
        )
    out.append("</svg>")
    return "\n".join(out) + "\n"
