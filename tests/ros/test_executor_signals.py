"""A signal that interrupts the executor's timed wait must not turn it into a hang.

CPython 3.11's ``SimpleQueue.get(timeout)``, which the executor once used, waits forever when a
signal handler runs past the wait's deadline; a node's loop then never sees its stop flag (the
simulator server ignored Ctrl-C that way on loaded machines).
"""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

CHILD = """
import signal, time
import launchkit.ros as ros

ros.init([])
node = ros.Node("waiter", enable_rosout=False, start_parameter_services=False)
stop = []


def handler(signum, frame):
    time.sleep(0.02)  # the timed wait's deadline passes while the handler runs
    stop.append(signum)


signal.signal(signal.SIGINT, handler)
turns = 0
while not stop:
    ros.spin_once(node, timeout_sec=0.01)  # nearly all of the loop is this timed wait
    turns += 1
    if turns == 20:
        print("ready", flush=True)
print("stopped", flush=True)
node.destroy_node()
ros.shutdown()
"""


def test_a_custom_signal_handler_stops_a_spin_once_loop(router: str, tmp_path: Path) -> None:
    script = tmp_path / "waiter.py"
    script.write_text(CHILD)
    for _ in range(3):
        child = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
        try:
            assert child.stdout is not None
            assert child.stdout.readline().strip() == "ready"
            child.send_signal(signal.SIGINT)
            assert child.wait(10) == 0, "the node did not leave its loop after SIGINT"
            assert child.stdout.read().strip() == "stopped"
        finally:
            if child.poll() is None:
                child.kill()
                child.wait()
            if child.stdout is not None:
                child.stdout.close()
