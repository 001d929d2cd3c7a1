"""The plot panel (rqt_plot) in a real browser: two fields of a topic typed in as rqt_plot takes
them follow the values the driver publishes (linear.x counting 0..19 over and over, angular.z
its negative), drawn in their colours; Pause freezes the chart, a drag zooms in on a span and a
double-click follows the newest samples again."""

from __future__ import annotations

import itertools
from typing import Any

from tests.viewer.conftest import Viewer, keep_screenshot, open_panel

LINEAR = "/robot1/cmd/linear/x"
ANGULAR = "/robot1/cmd/angular/z"


def state(viewer: Viewer) -> dict[str, Any]:
    """The plot's series (samples as plotted) and the x span shown."""
    return dict(viewer.page.evaluate("window.__viewer.tools.plot.state()"))


def series(viewer: Viewer, label: str) -> dict[str, Any]:
    """One series of the plot by its label."""
    return next(s for s in state(viewer)["series"] if s["label"] == label)


def add(viewer: Viewer, field: str) -> None:
    """Type a field into the panel and press Enter, as a person would."""
    box = viewer.page.locator("#plot-field")
    box.fill(field)
    box.press("Enter")


def coloured_pixels(viewer: Viewer, rgb: tuple[int, int, int]) -> int:
    """How many pixels of the chart's canvas are close to ``rgb``."""
    return int(
        viewer.page.evaluate(
            """([r, g, b]) => {
              const canvas = document.querySelector('#plot-area canvas');
              const data = canvas.getContext('2d')
                .getImageData(0, 0, canvas.width, canvas.height).data;
              let count = 0;
              for (let i = 0; i < data.length; i += 4) {
                if (Math.abs(data[i] - r) < 40 && Math.abs(data[i + 1] - g) < 40
                    && Math.abs(data[i + 2] - b) < 40) count += 1;
              }
              return count;
            }""",
            list(rgb),
        )
    )


def test_plotted_series_follow_the_published_values(panels_launch: Any, open_viewer: Any) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "plot")
    viewer.wait("s.connected && window.__viewer.tools.plot.topicsOf().length", "the topic list")
    add(viewer, LINEAR)
    add(viewer, ANGULAR)
    viewer.wait(
        "v.tools.plot.state().series.every((s) => s.values.length >= 40)",
        "40 samples in each series",
    )
    linear, angular = series(viewer, LINEAR), series(viewer, ANGULAR)
    values = linear["values"]
    assert all(v == int(v) and 0 <= v <= 19 for v in values), values
    # the driver counts up by one each message and wraps: what the plot holds does too
    steps = [b - a for a, b in itertools.pairwise(values)]
    assert sum(s in (1, -19) for s in steps) >= 0.9 * len(steps), values
    assert len(set(values)) >= 15, values
    at = dict(zip(angular["times"], angular["values"], strict=True))
    both = [(v, at[t]) for t, v in zip(linear["times"], values, strict=True) if t in at]
    assert len(both) >= 30 and all(z == -x for x, z in both), both[:5]
    assert linear["times"] == sorted(linear["times"])
    # drawn: the two series' colours are on the canvas
    assert coloured_pixels(viewer, (0x4F, 0xC3, 0xF7)) > 100
    assert coloured_pixels(viewer, (0xFF, 0xB7, 0x4D)) > 100
    now = state(viewer)
    shown, newest = now["x"], now["series"][0]["times"][-1]
    # the last 30 s, up to the newest sample (drawn at the next animation frame)
    assert 29 <= shown["max"] - shown["min"] <= 31 and abs(shown["max"] - newest) < 1.0, now
    keep_screenshot(viewer, "panel-plot")

    # pause: the chart keeps what it has while the driver goes on
    viewer.page.locator("#plot-pause").click()
    held = len(series(viewer, LINEAR)["values"])
    panels_launch.expect_topic("/robot1/cmd", min_messages=5, within=20)
    assert len(series(viewer, LINEAR)["values"]) == held
    viewer.page.locator("#plot-pause").click()
    viewer.wait(f"v.tools.plot.state().series[0].values.length > {held}", "samples again")

    # zoom: a drag across a part of the chart shows that part only, and stays there
    box = viewer.page.locator("#plot-area .u-over").bounding_box()
    assert box is not None
    y = box["y"] + box["height"] / 2
    viewer.page.mouse.move(box["x"] + box["width"] * 0.5, y)
    viewer.page.mouse.down()
    viewer.page.mouse.move(box["x"] + box["width"] * 0.7, y, steps=5)
    viewer.page.mouse.up()
    viewer.wait("!v.tools.plot.state().following", "the chart zoomed in")
    zoomed = state(viewer)["x"]
    assert 3 <= zoomed["max"] - zoomed["min"] <= 9, zoomed
    # a double-click follows the newest samples again
    viewer.page.mouse.dblclick(box["x"] + box["width"] * 0.5, y)
    viewer.wait("v.tools.plot.state().following", "the chart following again")

    # a series goes when removed, and its topic is no longer wanted by the page
    viewer.page.locator(f'.series-chip[data-series="{ANGULAR}"] button').click()
    assert [s["label"] for s in state(viewer)["series"]] == [LINEAR]
    add(viewer, "/robot1/cmd/no_such_field")
    viewer.wait(
        "v.tools.plot.state().series.some((s) => s.misses > 3)", "the unknown field unplotted"
    )
    viewer.page.locator('.series-chip[data-series="/robot1/cmd/no_such_field"] button').click()
    viewer.page.locator(f'.series-chip[data-series="{LINEAR}"] button').click()
    viewer.wait("!v.wanted().includes('/robot1/cmd')", "/robot1/cmd no longer wanted")
    assert not viewer.problems, viewer.problems
