"""``launchkit run`` hosts the router and its ``<node>`` processes talk (remaps, params)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from ros_helpers import NODES_DIR, Child, free_port


def _package(prefix: Path) -> None:
    """An AMENT_PREFIX_PATH package ``demo`` whose executables run the test nodes."""
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / "demo"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    (prefix / "share" / "demo").mkdir(parents=True)
    lib = prefix / "lib" / "demo"
    lib.mkdir(parents=True)
    for name in ("talker", "listener"):
        exe = lib / name
        script = str(NODES_DIR / f"{name}.py")
        exe.write_text(
            f"#!{sys.executable}\nimport runpy\nrunpy.run_path({script!r}, run_name='__main__')\n"
        )
        exe.chmod(0o755)


def test_launch_file_nodes_talk_through_the_hosted_router(
    tmp_path: Path, children: list[Child], monkeypatch: pytest.MonkeyPatch
) -> None:
    _package(tmp_path / "prefix")
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
    endpoint = f"tcp/127.0.0.1:{free_port()}"
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
