"""``launchkit bridge`` as a command: filters, clear errors, clean exit."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from bridge_helpers import BridgeProcess, DdsPeer, LaunchkitPeer, wait_until
from launchkit.ros.msgs.std_msgs.msg import String

from launchkit.bridge import _rclpy

pytestmark = pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")


def _bridge(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "launchkit", "bridge", *args],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, **(env or {})},
    )


def test_a_bad_regex_is_one_line_and_exit_2() -> None:
    result = _bridge("--topics", "/odom(")
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "--topics '/odom('" in lines[0] and "expected" in lines[0]


def test_without_rclpy_the_error_names_the_extra(tmp_path: Path) -> None:
    # a stand-in that makes `import rclpy` fail, as on a machine without the extra
    shadow = tmp_path / "rclpy"
    shadow.mkdir()
    (shadow / "__init__.py").write_text("raise ImportError('No module named rclpy')\n")
    result = _bridge(env={"PYTHONPATH": str(tmp_path)})
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "launchkit[ros2]" in lines[0] and "rclpy" in lines[0]


def test_on_a_platform_without_wheels_the_error_says_what_to_do(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(sys.modules, "rclpy", None)  # import rclpy -> ImportError
    monkeypatch.setattr(_rclpy, "wheels_supported", lambda: False)
    with pytest.raises(_rclpy.RclpyUnavailableError) as info:
        _rclpy.import_rclpy()
    text = info.value.format()
    assert "source a ROS 2 Jazzy install" in text and "CPython 3.11 on Linux x86_64" in text
    assert info.value.exit_status == 2


def test_only_the_chosen_topics_are_bridged(
    router: str, dds_domain: int, dds: DdsPeer, lk: LaunchkitPeer
) -> None:
    chosen = BridgeProcess(router, dds_domain, "--topics", "/pick/.*", "--exclude", "/pick/no")
    try:
        chosen.wait_line("bridging ROS_DOMAIN_ID")
        for name in ("/pick/no", "/other", "/pick/yes"):
            lk.node.create_publisher(String, name, 10)
        wait_until(lambda: "/pick/yes" in dds.topics(), 30, "/pick/yes on DDS")
        # the others were there first: had they been bridged, they would be seen by now
        assert "/pick/no" not in dds.topics() and "/other" not in dds.topics()
    finally:
        assert chosen.stop() == 0
    assert not any("bridging /other" in line for line in chosen.lines)


def test_rmw_zenoh_as_the_rmw_is_refused_with_the_way_that_needs_no_bridge() -> None:
    result = _bridge(env={"RMW_IMPLEMENTATION": "rmw_zenoh_cpp"})
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "RMW_IMPLEMENTATION=rmw_zenoh_cpp" in lines[0]
