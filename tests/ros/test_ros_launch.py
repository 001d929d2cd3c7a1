"""``launchkit run`` hosts the router and its ``<node>`` processes talk (remaps, params)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from ros_helpers import Child, demo_package

from launchkit.testing._isolation import free_loopback_port, router_endpoint


def test_launch_file_nodes_talk_through_the_hosted_router(
    tmp_path: Path, children: list[Child], monkeypatch: pytest.MonkeyPatch
) -> None:
    demo_package(tmp_path / "prefix")
    launch = tmp_path / "demo.launch.xml"
    launch.write_text(
        """<launch>
  <node pkg="demo" exec="talker" name="speaker" namespace="robot">
    <remap from="chatter" to="/news"/>
  </node>
  <node pkg="demo" exec="listener" output="screen">
    <remap from="chatter" to="news"/>
  </node>
</launch>
"""
    )
    endpoint = router_endpoint(free_loopback_port())
    launcher = Child(
        ["-m", "launchkit", "run", str(launch), "-a"],
        env={"AMENT_PREFIX_PATH": str(tmp_path / "prefix"), "LAUNCHKIT_ROUTER": endpoint},
    )
    children.append(launcher)
    launcher.expect(f"started the ROS router at {endpoint}", timeout=20)
    line = launcher.expect("heard: hello", timeout=20)
    assert line.startswith("[listener-2]")
    assert launcher.stop(timeout=10) == 0
    assert os.environ.get("LAUNCHKIT_ROUTER") != endpoint  # the test process was not touched
