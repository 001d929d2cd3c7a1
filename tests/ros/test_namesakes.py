"""Two nodes of one name in one graph (a launch started twice): both warn once they see each
other, and ``launchkit node list`` / ``node info`` show and say it, as ``ros2 node`` does."""

from __future__ import annotations

import subprocess
import sys
import time

from ros_helpers import NODES_DIR, Child

from launchkit.ros.keyexpr import domain_id

WARNING = (
    "[talker]: another node named '/talker' is in the graph too (ROS_DOMAIN_ID {domain}): "
    "the two share parameters and logs, and tools reach only one of them; is the same launch "
    "running twice? Rename one (--ros-args -r __node:=NAME, or a namespace)"
)


def launchkit(*args: str) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit ARGS`` to completion."""
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args], capture_output=True, text=True, timeout=30
    )


def wait_stderr(child: Child, text: str, timeout: float) -> None:
    """Wait until ``child`` has written ``text`` on stderr (its lines arrive on a thread)."""
    deadline = time.monotonic() + timeout
    while text not in "".join(child.stderr):
        assert time.monotonic() < deadline, f"no {text!r} within {timeout} s: {child.stderr}"
        time.sleep(0.05)


def test_two_nodes_of_one_name_in_the_graph_warn_and_the_tools_show_both(
    router_endpoint: str, children: list[Child]
) -> None:
    for _ in range(2):  # one after the other, as a launch run twice
        children.append(Child([str(NODES_DIR / "talker.py")]))
        children[-1].expect("talker ready", timeout=15)
    first, second = children
    for twin in (second, first):  # the one that joined, and the one already there
        wait_stderr(twin, WARNING.format(domain=domain_id()), timeout=10)

    listed = launchkit("node", "list")
    assert listed.returncode == 0 and listed.stdout.split() == ["/talker", "/talker"]
    assert listed.stderr == (
        "WARNING: more than one node in the graph is named /talker: tools reach only one of "
        "them, and they share parameters and logs\n"
    )
    info = launchkit("node", "info", "/talker")
    assert info.returncode == 0 and info.stdout.startswith("/talker\n")
    assert info.stderr.startswith("WARNING: 2 nodes in the graph are named /talker")
    for twin in (first, second):
        assert "".join(twin.stderr).count("another node named") == 1  # once
