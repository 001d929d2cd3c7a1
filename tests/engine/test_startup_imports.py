"""Start-up does only what the command needs: the modules a command imports are its own.

No timing here (that is bench/launch_overhead.py's job): these check which libraries a command
loads, which is what makes it slow or not, and which does not depend on the machine's load.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HEAVY = ("numpy", "rosbags", "yaml", "lxml", "zenoh", "pybullet", "launchkit.ros.node")

_PROBE = """
import json, sys
from launchkit.cli import main
status = main(sys.argv[1:])
loaded = sorted(m for m in {heavy!r} if m in sys.modules)
print("LOADED " + json.dumps(loaded), file=sys.stderr)
"""


def loaded_by(*argv: str) -> list[str]:
    """The heavy libraries ``launchkit ARGV`` imported (run to completion in a fresh process)."""
    result = subprocess.run(
        [sys.executable, "-c", _PROBE.format(heavy=HEAVY), *argv],
        capture_output=True,
        text=True,
        timeout=120,
    )
    line = [x for x in result.stderr.splitlines() if x.startswith("LOADED ")]
    assert line, result.stderr
    return list(json.loads(line[-1][len("LOADED ") :]))


def test_running_an_xml_file_loads_no_yaml_ros_or_simulation(tmp_path: Path) -> None:
    launch = tmp_path / "empty.launch.xml"
    launch.write_text("<launch>\n  <executable cmd='true'/>\n</launch>\n")
    assert loaded_by("run", str(launch)) == ["lxml"]


def test_running_a_yaml_file_loads_no_lxml(tmp_path: Path) -> None:
    launch = tmp_path / "empty.launch.yaml"
    launch.write_text("launch:\n- executable: {cmd: 'true'}\n")
    assert loaded_by("run", str(launch)) == ["yaml"]
