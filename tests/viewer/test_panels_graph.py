"""The node graph panel (rqt_graph) in a real browser, on panels.launch.py's nodes: the nodes
and the topic arrows between them, namespaces boxed, an action drawn as one box (or as its hidden
topics and services), services and the debug topics on demand."""

from __future__ import annotations

import json
from typing import Any

from tests.viewer.conftest import Viewer, keep_screenshot, open_panel


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
