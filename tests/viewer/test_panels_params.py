"""The parameters panel (rqt_reconfigure) in a real browser: a node's parameters with their
values and descriptors, as its own parameter services give them, and an edit in place that
changes the node's parameter (read back with ``launchkit param get``)."""

from __future__ import annotations

import os
import subprocess
import sys
from typing import Any

import launchkit.ros as ros
from launchkit.ros.msgs import get_service
from tests.viewer.conftest import Viewer, keep_screenshot, open_panel

NAMES = ["count", "enabled", "frozen", "label", "speed", "use_sim_time"]


def param_get(handle: Any, node: str, name: str) -> str:
    """``launchkit param get NODE NAME``'s output on the launch's network."""
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", "param", "get", node, name],
        env={**os.environ, **handle.ros_env},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def descriptors(handle: Any, node: str) -> dict[str, Any]:
    """What ``NODE/describe_parameters`` answers for NAMES, asked by a ROS client."""
    context = ros.Context(router=handle.router)
    context.init([], handle.domain_id)
    probe = ros.Node("params_test_probe", context=context, enable_rosout=False)
    try:
        srv = get_service("rcl_interfaces/srv/DescribeParameters")
        client = probe.create_client(srv, f"{node}/describe_parameters")
        assert client.wait_for_service(timeout_sec=30)
        response = client.call(srv.Request(names=NAMES), timeout_sec=30)
        return dict(zip(NAMES, response.descriptors, strict=True))
    finally:
        probe.destroy_node()
        context.shutdown()


def row(viewer: Viewer, name: str) -> dict[str, Any]:
    """A parameter's row as shown: value, type, description, whether it can be edited."""
    return dict(
        viewer.page.evaluate(
            """(name) => {
              const row = document.querySelector(`#params-table tr[data-param="${name}"]`);
              const editor = row.querySelector('[data-editor]');
              return { value: editor.type === 'checkbox' ? editor.checked : editor.value,
                       type: row.cells[2].textContent, description: row.cells[3].textContent,
                       disabled: editor.disabled, range: row.dataset.range || null,
                       result: row.querySelector('.set-result').textContent };
            }""",
            name,
        )
    )


def test_parameters_are_shown_and_edited_in_place(panels_launch: Any, open_viewer: Any) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "params")
    viewer.wait("document.querySelector('#params-nodes li[data-node=\"/tuner\"]')", "/tuner")
    viewer.page.locator('#params-nodes li[data-node="/tuner"]').click()
    viewer.wait(
        "document.querySelectorAll('#params-table tbody tr').length === 6", "six parameters"
    )
    shown = {name: row(viewer, name) for name in NAMES}
    assert shown["speed"]["value"] == "2.5" and shown["speed"]["type"] == "double"
    assert shown["count"]["value"] == "3" and shown["count"]["type"] == "integer"
    assert shown["label"]["value"] == "turtle" and shown["label"]["type"] == "string"
    assert shown["enabled"]["value"] is True and shown["use_sim_time"]["value"] is False
    # the descriptors as the node describes them: description, read-only, ranges
    for name, descriptor in descriptors(panels_launch, "/tuner").items():
        assert descriptor.description in shown[name]["description"], name
        assert shown[name]["disabled"] == bool(descriptor.read_only), name
        ranges = list(descriptor.floating_point_range) + list(descriptor.integer_range)
        expected = f"{ranges[0].from_value}..{ranges[0].to_value}" if ranges else None
        if expected is not None:
            assert shown[name]["range"] is not None, name
            low, high = (float(v) for v in shown[name]["range"].split(".."))
            assert (low, high) == (ranges[0].from_value, ranges[0].to_value), name
        else:
            assert shown[name]["range"] is None, name
    keep_screenshot(viewer, "panel-params")

    # an edit in place reaches the node
    editor = viewer.page.locator('#params-table [data-editor="speed"]')
    editor.fill("4.5")
    editor.press("Enter")
    viewer.wait("v.tools.params.sets >= 1", "the set_parameters call answered")
    assert row(viewer, "speed")["result"].strip() == "✓"
    assert param_get(panels_launch, "/tuner", "speed") == "Double value is: 4.5"
    label = viewer.page.locator('#params-table [data-editor="label"]')
    label.fill("crush")
    label.press("Enter")
    viewer.wait("v.tools.params.sets >= 2", "the second set answered")
    assert param_get(panels_launch, "/tuner", "label") == "String value is: crush"
    viewer.page.locator('#params-table [data-editor="enabled"]').uncheck()
    viewer.wait("v.tools.params.sets >= 3", "the third set answered")
    assert param_get(panels_launch, "/tuner", "enabled") == "Boolean value is: False"
    # a value of the wrong kind is refused by the page, naming why
    count = viewer.page.locator('#params-table [data-editor="count"]')
    count.fill("2.5")
    count.press("Enter")
    viewer.wait(
        "document.querySelector('#params-table tr[data-param=\"count\"] .set-result')"
        ".textContent.includes('not an integer')",
        "the refusal shown",
    )
    assert param_get(panels_launch, "/tuner", "count") == "Integer value is: 3"
    assert not viewer.problems, viewer.problems
