"""The panels of the viewer in a real browser, on one panels.launch.py and one Chromium shared
by the module's tests (each test opens its own page and reads or drives nodes of its own panel):
the node graph, the console, the plot, the parameters, and the service caller and publisher.

Each section below says what its panel's tests check."""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

import launchkit.ros as ros
from launchkit.ros.msgs import get_message, get_service
from tests.viewer.conftest import Viewer, keep_screenshot, open_panel

# The node graph panel (rqt_graph) in a real browser, on panels.launch.py's nodes: the nodes
# and the topic arrows between them, namespaces boxed, an action drawn as one box (or as its hidden
# topics and services), services and the debug topics on demand.


def drawn(viewer: Viewer) -> dict[str, Any]:
    """What the SVG shows now: node ids with their cluster, and arrows as (from, to)."""
    return dict(
        viewer.page.evaluate(
            """() => ({
              nodes: Object.fromEntries([...document.querySelectorAll('#graph-svg g.gnode')]
                .map((g) => [g.dataset.id, g.getBoundingClientRect().width > 0])),
              edges: [...document.querySelectorAll('#graph-svg path.gedge')]
                .map((p) => [p.dataset.from, p.dataset.to]),
              clusters: [...document.querySelectorAll('#graph-svg g.gcluster')]
                .map((g) => g.dataset.id),
            })"""
        )
    )


def wait_drawn(viewer: Viewer, ids: list[str], what: str) -> dict[str, Any]:
    """Wait until every id in ``ids`` is drawn; what is drawn then."""
    check = " && ".join(
        f"document.querySelector('#graph-svg g.gnode[data-id={json.dumps(i)}]')" for i in ids
    )
    viewer.wait(check, what)
    return drawn(viewer)


def inside(viewer: Viewer, node: str, cluster: str) -> bool:
    """Whether ``node``'s shape lies within ``cluster``'s box on the screen."""
    return bool(
        viewer.page.evaluate(
            """([node, cluster]) => {
              const a = document.querySelector(`#graph-svg g.gnode[data-id="${node}"]`)
                .getBoundingClientRect();
              const b = document.querySelector(`#graph-svg g.gcluster[data-id="${cluster}"] rect`)
                .getBoundingClientRect();
              return a.left >= b.left && a.right <= b.right && a.top >= b.top
                && a.bottom <= b.bottom;
            }""",
            [node, cluster],
        )
    )


def option(viewer: Viewer, name: str, on: bool) -> None:
    """Tick or untick one of the panel's options."""
    box = viewer.page.locator(f'#graph-panel input[data-option="{name}"]')
    box.check() if on else box.uncheck()


def test_the_graph_shows_nodes_topics_namespaces_and_actions(
    panels_launch: Any, open_viewer: Any
) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "graph")
    shown = wait_drawn(
        viewer,
        ["n:/talker", "t:/chatter", "n:/listener", "n:/robot1/driver", "a:/fibonacci"],
        "the talker, its topic, the listener, the namespaced driver and the action drawn",
    )
    edges = {tuple(e) for e in shown["edges"]}
    # publisher -> topic -> subscriber
    assert ("n:/talker", "t:/chatter") in edges and ("t:/chatter", "n:/listener") in edges
    assert ("n:/robot1/driver", "t:/robot1/cmd") in edges
    assert ("t:/robot1/cmd", "n:/robot1/follower") in edges
    # the namespace /robot1 boxes its nodes and topics, and nothing else
    assert "ns:/robot1" in shown["clusters"]
    for member in ("n:/robot1/driver", "n:/robot1/follower", "t:/robot1/cmd"):
        assert inside(viewer, member, "ns:/robot1"), member
    assert not inside(viewer, "n:/talker", "ns:/robot1")
    # the action as one box, from its server to its client; its parts are hidden names
    assert ("n:/fibonacci", "a:/fibonacci") in edges and ("a:/fibonacci", "n:/fib_client") in edges
    assert not any("_action" in node for node in shown["nodes"])
    # debug topics and the viewer itself are left out by default, services are not drawn
    assert "t:/rosout" not in shown["nodes"] and "n:/rviz2" not in shown["nodes"]
    assert not any(node.startswith("s:") for node in shown["nodes"])
    keep_screenshot(viewer, "panel-graph")

    # the action's parts, when actions are not grouped and hidden names are shown
    option(viewer, "groupActions", False)
    option(viewer, "hideHidden", False)
    shown = wait_drawn(
        viewer, ["t:/fibonacci/_action/feedback"], "the action's feedback topic drawn"
    )
    edges = {tuple(e) for e in shown["edges"]}
    assert ("n:/fibonacci", "t:/fibonacci/_action/status") in edges
    assert ("t:/fibonacci/_action/status", "n:/fib_client") in edges
    assert "a:/fibonacci" not in shown["nodes"]

    # services (caller -> service -> server) and the debug topics, on demand
    option(viewer, "groupActions", True)
    option(viewer, "hideHidden", True)
    option(viewer, "services", True)
    option(viewer, "hideDebug", False)
    shown = wait_drawn(viewer, ["s:/tuner/shout", "t:/rosout"], "a service and /rosout drawn")
    edges = {tuple(e) for e in shown["edges"]}
    assert ("s:/tuner/shout", "n:/tuner") in edges
    assert ("n:/logger", "t:/rosout") in edges and ("t:/rosout", "n:/rviz2") not in edges
    assert "s:/tuner/set_parameters" in shown["nodes"]

    # no topic boxes: one labelled arrow per topic from node to node (rqt_graph's Nodes only)
    option(viewer, "topics", False)
    viewer.wait(
        "!document.querySelector('#graph-svg g.gnode.topic') && "
        "document.querySelector('#graph-svg path.gedge[data-label=\"/chatter\"]')",
        "the topics folded into labelled arrows",
    )
    edges = {tuple(e) for e in drawn(viewer)["edges"]}
    assert ("n:/talker", "n:/listener") in edges
    assert not viewer.problems, viewer.problems


# The console panel (rqt_console) in a real browser: /rosout's lines appear as they are logged
# (from any publisher of the topic; panel_nodes.py's logger and follower publish it themselves),
# and the severity, node and text filters hide and show them; Pause holds new lines back.


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


# The plot panel (rqt_plot) in a real browser: two fields of a topic typed in as rqt_plot takes
# them follow the values the driver publishes (linear.x counting 0..19 over and over, angular.z
# its negative), drawn in their colours; Pause freezes the chart, a drag zooms in on a span and a
# double-click follows the newest samples again.


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


# The parameters panel (rqt_reconfigure) in a real browser: a node's parameters with their
# values and descriptors, as its own parameter services give them, and an edit in place that
# changes the node's parameter (read back with ``launchkit param get``).


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


# The service caller and the topic publisher panels in a real browser: a call built in the
# form returns the service's response, shown; a message built in the form reaches a subscriber,
# once or at a rate until stopped.


def test_a_service_call_from_the_form_shows_the_response(
    panels_launch: Any, open_viewer: Any
) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "services")
    viewer.wait(
        "[...document.querySelectorAll('#call-service option')]"
        ".some((o) => o.value === '/tuner/shout')",
        "/tuner/shout listed",
    )
    viewer.page.locator("#call-service").select_option("/tuner/shout")
    viewer.wait("!document.querySelector('#call-button').disabled", "the request form")
    # the form has the request's one field, a bool
    assert viewer.page.locator("#call-form input[data-path]").count() == 1
    viewer.page.locator('#call-form input[data-path="data"]').check()
    viewer.page.locator("#call-button").click()
    viewer.wait("v.tools.services.calls >= 1", "the first response")
    shown = viewer.page.locator("#call-response")
    assert shown.get_attribute("data-state") == "ok"
    assert json.loads(shown.inner_text()) == {"success": True, "message": "shouting: on"}
    keep_screenshot(viewer, "panel-services")
    viewer.page.locator('#call-form input[data-path="data"]').uncheck()
    viewer.page.locator("#call-button").click()
    viewer.wait("v.tools.services.calls >= 2", "the second response")
    assert json.loads(shown.inner_text())["message"] == "shouting: off"
    assert not viewer.problems, viewer.problems


def test_a_message_from_the_form_reaches_a_subscriber(panels_launch: Any, open_viewer: Any) -> None:
    viewer = open_panel(open_viewer, panels_launch.viewer_url, "publisher")
    viewer.page.locator("#pub-topic").fill("/robot1/say")
    type_box = viewer.page.locator("#pub-type")
    type_box.fill("std_msgs/msg/String")
    type_box.press("Enter")
    viewer.wait("!document.querySelector('#pub-once').disabled", "the message form")
    viewer.page.locator('#pub-form input[data-path="data"]').fill("from the form")
    viewer.page.locator("#pub-rate").fill("5")
    viewer.page.locator("#pub-start").click()
    got = panels_launch.expect_topic(
        "/robot1/say", min_messages=3, within=30, where=lambda m: m.data == "from the form"
    )
    assert all(m.data == "from the form" for m in got)
    keep_screenshot(viewer, "panel-publisher")
    # stopped: the list empties and nothing more is sent
    viewer.page.locator('#pub-running li[data-topic="/robot1/say"] button').click()
    sent = viewer.page.evaluate("window.__viewer.tools.publisher.sent")
    viewer.page.wait_for_timeout(600)  # two periods at 5 Hz, to see that none more are sent
    assert viewer.page.evaluate("window.__viewer.tools.publisher.sent") == sent
    assert viewer.page.locator("#pub-running li").count() == 0

    # a topic of the graph brings its type; a field that does not fit its type is named, and
    # nothing is sent
    viewer.page.locator("#pub-topic").fill("/robot1/cmd")
    viewer.page.locator("#pub-topic").press("Enter")
    viewer.wait(
        "document.querySelector('#pub-form input[data-path=\"linear.x\"]') && "
        "!document.querySelector('#pub-once').disabled",
        "the Twist form",
    )
    assert type_box.input_value() == "geometry_msgs/msg/Twist"
    viewer.page.locator("#pub-topic").fill("/robot1/joints")
    type_box.fill("sensor_msgs/msg/JointState")
    type_box.press("Enter")
    viewer.wait(
        "document.querySelector('#pub-form input[data-path=\"position\"]') && "
        "!document.querySelector('#pub-once').disabled",
        "the JointState form",
    )
    viewer.page.locator('#pub-form input[data-path="position"]').fill("[1.0, 2.0")
    viewer.page.locator("#pub-once").click()
    assert "position" in viewer.page.locator("#pub-status").inner_text()
    assert viewer.page.evaluate("window.__viewer.tools.publisher.sent") == sent
    assert not viewer.problems, viewer.problems
