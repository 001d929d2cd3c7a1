"""The console panel (rqt_console) in a real browser: /rosout's lines appear as they are logged
(from any publisher of the topic; panel_nodes.py's logger and follower publish it themselves),
and the severity, node and text filters hide and show them; Pause holds new lines back."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import pytest

import launchkit.ros as ros
from launchkit.ros.msgs import get_message
from tests.viewer.conftest import Viewer, keep_screenshot, open_panel

String = get_message("std_msgs/msg/String")


def rows(viewer: Viewer) -> list[dict[str, str]]:
    """The table's rows as shown: severity, node and message."""
    return list(
        viewer.page.evaluate(
            """() => [...document.querySelectorAll('#console-table tbody tr')].map((r) => ({
              severity: r.cells[1].textContent, node: r.cells[2].textContent,
              message: r.cells[4].textContent, visible: r.getBoundingClientRect().height > 0 }))"""
        )
    )


def shown_with(viewer: Viewer, text: str) -> str:
    """A page expression: whether a row whose message contains ``text`` is in the table."""
    return (
        "[...document.querySelectorAll('#console-table tbody tr')]"
        f".some((r) => r.cells[4].textContent.includes({json.dumps(text)}))"
    )


@pytest.fixture
def say(panels_launch: Any) -> Iterator[Any]:
    """Publish a String on /robot1/say (the follower logs what it hears)."""
    context = ros.Context(router=panels_launch.router)
    context.init([], panels_launch.domain_id)
    node = ros.Node("console_test_speaker", context=context, enable_rosout=False)
    publisher = node.create_publisher(String, "/robot1/say", 10)
    assert context.graph.wait_for(lambda: publisher.get_subscription_count() > 0, 30)
    try:
        yield lambda text: publisher.publish(String(data=text))
    finally:
        node.destroy_node()
        context.shutdown()


def test_log_lines_appear_and_the_filters_hide_and_show_them(
    panels_launch: Any, open_viewer: Any, say: Any
) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "console")
    for severity in ("DEBUG", "INFO", "WARN", "ERROR", "FATAL"):
        viewer.wait(shown_with(viewer, f"at {severity}"), f"a logger line at {severity}")
    by_severity = {r["severity"] for r in rows(viewer) if r["node"] == "logger"}
    assert by_severity == {"Debug", "Info", "Warn", "Error", "Fatal"}, by_severity

    # a line logged now appears, with its node's name
    say("hello console")
    viewer.wait(shown_with(viewer, "heard: hello console"), "the follower's line")
    (line,) = [r for r in rows(viewer) if r["message"] == "heard: hello console"]
    assert line["node"] == "follower" and line["severity"] == "Info" and line["visible"]
    keep_screenshot(viewer, "panel-console")

    # severity: without Info the line is gone, and back with it
    viewer.page.locator('#console-panel input[data-level="20"]').uncheck()
    viewer.wait(f"!({shown_with(viewer, 'heard: hello console')})", "the Info line hidden")
    assert all(r["severity"] != "Info" for r in rows(viewer))
    viewer.page.locator('#console-panel input[data-level="20"]').check()
    viewer.wait(shown_with(viewer, "heard: hello console"), "the Info line shown again")

    # node: only the follower's lines
    viewer.page.locator("#console-node").select_option("follower")
    viewer.wait(f"!({shown_with(viewer, 'at WARN')})", "the logger's lines hidden")
    assert {r["node"] for r in rows(viewer)} == {"follower"}
    viewer.page.locator("#console-node").select_option("")

    # text: only lines containing it
    viewer.page.locator("#console-search").fill("at warn")
    viewer.wait(f"!({shown_with(viewer, 'at ERROR')})", "lines without 'at warn' hidden")
    assert rows(viewer) and all("at WARN" in r["message"] for r in rows(viewer))
    viewer.page.locator("#console-search").fill("")

    # pause: new lines are held back, and shown on resume
    viewer.page.locator("#console-pause").click()
    held = "document.querySelector('#console-status').textContent"
    viewer.wait(f"/paused, [1-9]\\d* new held back/.test({held})", "new lines held back")
    say("said while paused")
    viewer.wait(f"/paused, [3-9]\\d* new held back/.test({held})", "more lines held back")
    assert not any(r["message"] == "heard: said while paused" for r in rows(viewer))
    viewer.page.locator("#console-pause").click()
    viewer.wait(shown_with(viewer, "heard: said while paused"), "the held line shown on resume")
    assert not viewer.problems, viewer.problems
