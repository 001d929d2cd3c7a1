"""launchkit.testing: process tests for launch files, as a pytest plugin.

Installing launchkit registers the plugin (entry point ``pytest11: launchkit``), which gives
tests the ``launch`` fixture (and ``launch_module`` for launches shared by a module)::

    def test_talker_greets(launch):
        handle = launch("robot_wheel", "hello.launch.xml", args={"count": 2})
        handle.process("talker").wait_output("Hello number 2", timeout=5)
        assert handle.process("talker").wait_exit(timeout=5) == 0
        handle.stop().assert_exit_codes({"talker": 0})

See ``docs/testing.md``.
"""

from launchkit.testing._errors import (
    ExitCodeMismatch,
    LaunchFailed,
    LaunchTestError,
    ProcessDied,
    ProcessLeftBehind,
    UnexpectedExit,
    WaitTimeout,
)
from launchkit.testing._factory import LaunchFactory
from launchkit.testing._handle import LaunchHandle
from launchkit.testing._matchers import InOrder, Matcher, in_order
from launchkit.testing._process import ProcessHandle
from launchkit.testing._result import LaunchResult

__all__ = [
    "ExitCodeMismatch",
    "InOrder",
    "LaunchFactory",
    "LaunchFailed",
    "LaunchHandle",
    "LaunchResult",
    "LaunchTestError",
    "Matcher",
    "ProcessDied",
    "ProcessHandle",
    "ProcessLeftBehind",
    "UnexpectedExit",
    "WaitTimeout",
    "in_order",
]
