"""What the test plugin raises. Every error is an ``AssertionError``, so pytest reports it as a
test failure (not an error in the test's own code) and ``pytest.raises`` can catch it.

::

    LaunchTestError        anything launchkit.testing reports
    ├── LaunchFailed       the launch failed before it was ready (launchkit's own message)
    ├── WaitTimeout        a wait ran past its deadline
    ├── ProcessDied        a process (or the launch) ended while a wait needed it
    │   └── UnexpectedExit a process died and the test never took note of it (at teardown)
    ├── ExitCodeMismatch   ``LaunchResult.assert_exit_codes`` found unexpected exit codes
    └── ProcessLeftBehind  a process of the launch survived its teardown
"""

from __future__ import annotations


class LaunchTestError(AssertionError):
    """Base of everything launchkit.testing reports; the message carries the evidence."""


class LaunchFailed(LaunchTestError):
    """The launch failed before it was ready: a bad file, a missing argument, a crash."""


class WaitTimeout(LaunchTestError):
    """A wait ran past its deadline; says what was awaited and shows every process."""


class ProcessDied(LaunchTestError):
    """A wait can no longer succeed: its process exited, the launch failed or ended, or a
    required process died."""


class UnexpectedExit(ProcessDied):
    """At teardown: a process died unexpectedly and the test never took note of it (with
    ``wait_exit``, ``returncode``, the result's ``exit_codes`` / ``assert_exit_codes``, or
    ``launch(..., allow_exit=...)``)."""


class ExitCodeMismatch(LaunchTestError):
    """Processes exited with codes the test did not expect."""


class ProcessLeftBehind(LaunchTestError):
    """A process of the launch was still alive after teardown (it has been killed since)."""


for _error in (
    LaunchTestError,
    LaunchFailed,
    WaitTimeout,
    ProcessDied,
    UnexpectedExit,
    ExitCodeMismatch,
    ProcessLeftBehind,
):
    _error.__module__ = "launchkit.testing"  # reports name the public path
