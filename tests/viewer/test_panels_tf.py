"""The TF tree panel (view_frames) in a real browser on the seed robot (display.launch.xml):
every frame with its parent, the rate its transform comes at, and the tree drawn; and
``launchkit tf view-frames`` writing the tree as ``frames_<time>.gv`` with a PDF (Graphviz) or,
without Graphviz, an SVG picture."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest

from launchkit.testing._isolation import free_loopback_port
from tests.viewer.conftest import keep_screenshot, open_panel

# the seed robot's frames: its continuous joints move (robot_state_publisher's /tf), its fixed
# ones do not (/tf_static)
MOVING = ["caster", "wheel_left_link", "wheel_right_link"]
FIXED = ["camera", "lidar"]


@pytest.fixture(scope="module")
def robot(launch_module: Any) -> Any:
    """display.launch.xml (robot_state_publisher, joint_state_publisher_gui, rviz2), serving."""
    port = free_loopback_port()
    handle = launch_module(
        "robot_wheel",
        "display.launch.xml",
        env={"LAUNCHKIT_VIEWER_PORT": str(port)},
        ready_timeout=60,
    )
    handle.process("rviz2").wait_output("Foxglove WebSocket on", timeout=60)
    handle.viewer_url = f"http://127.0.0.1:{port}/"
    return handle


def test_the_tf_tree_lists_the_frames_with_parents_and_rates(robot: Any, open_viewer: Any) -> None:
    viewer = open_panel(open_viewer, robot.viewer_url, "tf")
    frames = MOVING + FIXED
    viewer.wait(
        " && ".join(f"document.querySelector('#tf-table tr[data-frame=\"{f}\"]')" for f in frames)
        + " && [...document.querySelectorAll('#tf-table tbody tr')]"
        ".every((r) => r.cells[2].textContent !== '0.0')",
        "every frame listed, with its rate",
    )
    rows = {
        r["frame"]: r
        for r in viewer.page.evaluate(
            """() => [...document.querySelectorAll('#tf-table tbody tr')].map((r) => ({
              frame: r.cells[0].textContent, parent: r.cells[1].textContent,
              rate: r.cells[2].textContent }))"""
        )
    }
    assert sorted(rows) == sorted(frames)
    assert all(rows[f]["parent"] == "base" for f in frames), rows
    assert all(rows[f]["rate"] == "static" for f in FIXED), rows
    assert all(float(rows[f]["rate"]) > 1 for f in MOVING), rows
    # the tree drawn: base first (at the left), an arrow from it to each frame, right of it
    drawn = viewer.page.evaluate(
        """() => ({
          nodes: Object.fromEntries([...document.querySelectorAll('#tf-svg g.gnode')].map((g) =>
            [g.dataset.id, g.getBoundingClientRect().left])),
          edges: [...document.querySelectorAll('#tf-svg path.gedge')]
            .map((p) => [p.dataset.from, p.dataset.to]),
        })"""
    )
    assert sorted(drawn["nodes"]) == sorted(["base", *frames])
    assert sorted(map(tuple, drawn["edges"])) == sorted(("base", f) for f in frames)
    assert all(drawn["nodes"][f] > drawn["nodes"]["base"] for f in frames)
    assert "root base" in viewer.page.locator("#tf-summary").inner_text()
    keep_screenshot(viewer, "panel-tf")
    assert not viewer.problems, viewer.problems


def view_frames(robot: Any, folder: Path, path: str) -> subprocess.CompletedProcess[str]:
    """``launchkit tf view-frames -t 2`` in ``folder`` with ``PATH`` as given."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", "tf", "view-frames", "-t", "2"],
        cwd=folder,
        env={**os.environ, **robot.ros_env, "PATH": path},
        capture_output=True,
        text=True,
        timeout=120,
    )


def test_view_frames_without_graphviz_writes_the_tree_as_gv_and_svg(
    robot: Any, tmp_path: Path
) -> None:
    # a PATH without Graphviz's dot (the interpreter is called by its full path)
    done = view_frames(robot, tmp_path, str(tmp_path / "nothing-here"))
    assert done.returncode == 0, done.stderr
    (gv,) = tmp_path.glob("frames_*.gv")
    assert re.fullmatch(r"frames_\d{4}-\d\d-\d\d_\d\d\.\d\d\.\d\d\.gv", gv.name)
    assert re.search(
        r"^\[INFO\] \[[\d.]+\] \[view_frames\]: Listening to tf data for 2.0 seconds\.\.\.$",
        done.stderr,
        re.M,
    ), done.stderr
    assert "dot is not installed" in done.stderr
    edges = dict(
        (child, parent)
        for parent, child in re.findall(r'^"([^"]+)" -> "([^"]+)"\[', gv.read_text(), re.M)
    )
    assert edges == {f: "base" for f in MOVING + FIXED}, gv.read_text()
    svg = ET.parse(gv.with_suffix(".svg")).getroot()
    ns = "{http://www.w3.org/2000/svg}"
    drawn = {g.get("data-frame") for g in svg.iter(f"{ns}g")}
    assert drawn == {"base", *MOVING, *FIXED}
    labels = [t.text or "" for t in svg.iter(f"{ns}text")]
    assert sum(label.startswith("Broadcaster: ") for label in labels) == 5
    assert not list(tmp_path.glob("*.pdf"))


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz's dot is not installed")
def test_view_frames_with_graphviz_writes_a_pdf(robot: Any, tmp_path: Path) -> None:
    done = view_frames(robot, tmp_path, os.environ["PATH"])
    assert done.returncode == 0, done.stderr
    (pdf,) = tmp_path.glob("frames_*.pdf")
    assert pdf.read_bytes().startswith(b"%PDF")
    assert pdf.with_suffix(".gv").is_file() and not list(tmp_path.glob("*.svg"))
