"""Start-up does only what the command needs: a launch loads neither the ROS layer nor the
simulator, and a launch that starts nothing makes no run folder and binds no socket (that a
node process does not load the launch engine is tests/test_public_api.py's).

No timing here (that is bench/launch_overhead.py's job): these check which libraries a process
loads and what it creates, which is what makes it slow or not, and which does not depend on
the machine's load.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

#: What a launch of files that start no node has no use for.
ROS_AND_SIMULATION = ("numpy", "rosbags", "zenoh", "pybullet", "launchkit.ros.node")

_PROBE = """
import json, socket, sys, tempfile
made = []
mkdtemp, bind = tempfile.mkdtemp, socket.socket.bind
def recorded_mkdtemp(*args, **kwargs):
    made.append("folder")
    return mkdtemp(*args, **kwargs)
def recorded_bind(self, address):
    made.append("socket")
    return bind(self, address)
tempfile.mkdtemp, socket.socket.bind = recorded_mkdtemp, recorded_bind
from launchkit.cli import main
status = main(sys.argv[1:])
loaded = sorted(m for m in sys.modules if m in {modules!r})
print("LOADED " + json.dumps([loaded, sorted(set(made))]), file=sys.stderr)
"""


def launched(*argv: str) -> tuple[list[str], list[str]]:
    """Which of :data:`ROS_AND_SIMULATION` ``launchkit ARGV`` imported, and what it made of
    a temporary folder and a bound socket (run to completion in a fresh process)."""
    probe = _PROBE.format(modules=ROS_AND_SIMULATION)
    result = subprocess.run(
        [sys.executable, "-c", probe, *argv], capture_output=True, text=True, timeout=120
    )
    line = [x for x in result.stderr.splitlines() if x.startswith("LOADED ")]
    assert line, result.stderr
    loaded, made = json.loads(line[-1][len("LOADED ") :])
    return loaded, made


def test_a_launch_loads_no_ros_layer_or_simulation(tmp_path: Path) -> None:
    xml = tmp_path / "one.launch.xml"
    xml.write_text("<launch>\n  <executable cmd='true'/>\n</launch>\n")
    assert launched("run", str(xml))[0] == []
    yaml = tmp_path / "one.launch.yaml"
    yaml.write_text("launch:\n- executable: {cmd: 'true'}\n")
    assert launched("run", str(yaml))[0] == []


def test_a_launch_that_starts_nothing_makes_no_run_folder_or_socket(tmp_path: Path) -> None:
    # The private run folder (and the orphan guard told about it) and the child-request
    # socket are made when the first process starts.
    launch = tmp_path / "empty.launch.xml"
    launch.write_text(
        "<launch><let name='a' value='$(var b)'/><arg name='b' default='1'/></launch>\n"
    )
    assert launched("run", str(launch))[1] == []
    started = tmp_path / "one.launch.xml"
    started.write_text("<launch><executable cmd='true'/></launch>\n")
    assert launched("run", str(started))[1] == ["folder", "socket"]
