"""While the lockstep time stands still (a process not joined yet, a callback that never
returns), the launch stays in the test's and the user's hands: a process that is not a
launchkit node is named as outside the lockstep and no longer waited for, a wait for simulated
time fails at its wall deadline saying where the time stands, and Ctrl-C stops everything."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from launchkit.testing import WaitTimeout

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

LAUNCH = Path(__file__).parent / "launch" / "outside.launch.xml"


def test_time_standing_still_leaves_the_launch_in_hand(launch) -> None:  # type: ignore[no-untyped-def]
    handle = launch(LAUNCH, env={"PYTHON": sys.executable}, lockstep=True, allow_exit=["*"])
    # the shell process never joins: after the grace the time goes on without it
    handle.advance(0.25, timeout=60)
    log = handle.launcher_log.read_text()
    assert re.search(r"sleeper-3 \[pid \d+\] is outside the lockstep", log), log
    handle.process("ticker").wait_output("tick 1 at 250000000", timeout=10)
    # the stuck node's callback at 0.5 s never returns: the time stands there
    with pytest.raises(WaitTimeout, match=r"stands at 0\.500 s, short of 1\.250 s"):
        handle.advance(1.0, timeout=3)
    handle.process("stuck").wait_output("hanging at 500000000", timeout=5)
    assert handle.sim_time == 0.5
    result = handle.stop(timeout=20)  # Ctrl-C: every process goes, the stuck one too
    assert set(result.exit_codes) == {"ticker", "stuck", "sleeper"}
    assert result.returncode is not None
