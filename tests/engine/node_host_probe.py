"""A node for tests/engine/test_node_host.py: says what it was given and exits as asked.

python -m tests.engine.node_host_probe STATUS|wait ARGS...
"""

from __future__ import annotations

import os
import sys
import time

# A node forked from the host finds numpy imported already; a cold one does not.
preloaded = "numpy" in sys.modules
line = sys.stdin.readline().strip()
print(
    f"argv={sys.argv[1:]} cwd={os.getcwd()} env={os.environ.get('PROBE_VAR')} "
    f"stdin={line} preloaded={preloaded} pid={os.getpid()}",
    flush=True,
)
print("probe on stderr", file=sys.stderr, flush=True)
if sys.argv[1] == "wait":
    while True:
        time.sleep(1)
sys.exit(int(sys.argv[1]))
