"""rviz2's start-up mistakes: each is one line and exit status 2, nothing left serving."""

from __future__ import annotations

import socket
from pathlib import Path

from tests.stock.conftest import Processes


def _fails(processes: Processes, *args: str) -> str:
    proc = processes.start("launchkit.stock.rviz2.node", *args)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 2, err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if "error" in line]
    assert len(lines) == 1, err
    return lines[0]


def test_missing_config_is_one_line_exit_2(processes: Processes, tmp_path: Path) -> None:
    line = _fails(processes, "-d", str(tmp_path / "none.rviz"))
    assert "cannot read the display config" in line


def test_a_busy_port_is_one_line_exit_2(processes: Processes) -> None:
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        proc = processes.start("launchkit.stock.rviz2.node", "--port", str(port))
        _, err = proc.communicate(timeout=30)
    assert proc.returncode == 2 and "Traceback" not in err, err
    # says why, and how to choose another port where the user chose this one
    assert err.splitlines() == [
        f"rviz2: error: cannot serve the viewer on 127.0.0.1:{port}: the port is already in use "
        "(another viewer, or another program, listens there) (expected a free port)",
        "  hint: choose another port: viewer_port:=N on the robot's launch (launchkit run "
        "gazebo_and_rviz.launch.xml viewer_port:=8766; 0 picks a free one), else rviz2's port "
        "parameter, its --port N, or $LAUNCHKIT_VIEWER_PORT",
    ]


def test_a_port_parameter_of_the_wrong_type_is_one_line_exit_2(processes: Processes) -> None:
    line = _fails(processes, "--ros-args", "-p", "port:=eighty")
    assert "parameter 'port'" in line and "expected a port number" in line
