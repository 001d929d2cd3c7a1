"""A wait's outcome depends only on its own condition; other deaths are evidence, and a death
the test never took note of fails it at teardown (docs/testing.md, "When a wait fails").

``stress_waits.py`` beside this file repeats the first test many times under load (by hand).
"""

from __future__ import annotations

import pytest

from launchkit.testing import LaunchHandle, ProcessDied, WaitTimeout
from tests.testing.conftest import LAUNCH_DIR


def _await_death(handle: LaunchHandle, name: str) -> None:
    """Wait until process ``name`` has exited, without taking note of its exit (as a test
    that never looks at it would not)."""

    def dead() -> bool | None:
        return any(not record.running for record in handle.state.find(name)) or None

    handle.waits.until(f"process '{name}' to exit (unnoted)", 10, dead)


def test_talk(launch):
    # issue #9's launch_testing idiom: flaky (ProcessDied) while "any death fails every wait"
    h = launch("launch/talk.launch.xml")
    h.process("talker").wait_output("said-hi", timeout=10)
    assert h.process("quitter").wait_exit(timeout=10) == 3
    assert h.stop().exit_codes["quitter"] == 3


def test_a_wait_holding_already_succeeds_whatever_died(launch):
    h = launch("launch/talk.launch.xml")
    _await_death(h, "quitter")
    assert h.process("talker").wait_output("said-hi", timeout=10) == "said-hi"
    assert h.process("talker").wait_running(timeout=10) == h.process("talker").pid
    h.stop().assert_exit_codes({"talker": -2, "quitter": 3})


def test_a_wait_that_never_holds_fails_at_its_deadline_naming_the_death(launch):
    h = launch("launch/talk.launch.xml")
    talker = h.process("talker")
    _await_death(h, "quitter")
    with pytest.raises(WaitTimeout) as caught:
        talker.wait_output("said-bye", timeout=0.5)  # the talker never says it
    message = str(caught.value)
    assert message.startswith(
        "timed out after 0.5 s waiting for a line containing 'said-bye' from process 'talker'"
    )
    assert "a likely cause: process quitter-2 died unexpectedly: exited with exit code 3" in (
        message
    )
    assert h.process("quitter").wait_exit(timeout=5) == 3
    with pytest.raises(WaitTimeout) as caught:
        talker.wait_output("said-bye", timeout=0.1)
    assert "likely cause" not in str(caught.value)  # noted: no longer a suspect


def test_a_required_process_dying_ends_every_wait_at_once(launch):
    h = launch("launch/required.launch.xml")
    with pytest.raises(ProcessDied) as caught:
        h.process("steady").wait_output("a line that never comes", timeout=60)
    assert (
        'process crasher-2, which the launch requires (on_exit="shutdown"), died: '
        "exited with exit code 3"
    ) in str(caught.value)
    h.stop().assert_exit_codes({"steady": 0, "crasher": 3})


def test_deaths_the_test_never_noted_fail_it_at_teardown(pytester):
    talk = LAUNCH_DIR / "talk.launch.xml"
    pytester.makepyfile(
        f"""
        TALK = {str(talk)!r}

        def launch_and_await_the_quitter(launch, **options):
            h = launch(TALK, **options)
            dead = lambda: any(not r.running for r in h.state.find("quitter")) or None
            h.waits.until("the quitter to exit", 10, dead)  # without taking note of it
            return h

        def test_unnoted(launch):
            launch_and_await_the_quitter(launch)

        def test_allowed(launch):
            launch_and_await_the_quitter(launch, allow_exit={{"quitter": 3}})

        def test_allowed_with_another_code(launch):
            launch_and_await_the_quitter(launch, allow_exit={{"quitter": {{0, 4}}}})

        def test_exit_codes_read(launch):
            assert launch_and_await_the_quitter(launch).stop().exit_codes["quitter"] == 3

        def test_failing_anyway(launch):
            h = launch_and_await_the_quitter(launch)
            h.process("talker").wait_output("said-bye", timeout=0.2)
        """
    )
    result = pytester.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(passed=4, failed=1, errors=2)  # teardown errors count too
    result.stdout.fnmatch_lines_random(
        [
            "*ERROR at teardown of test_unnoted*",
            "*ERROR at teardown of test_allowed_with_another_code*",
            "E *launchkit.testing.UnexpectedExit: process quitter-2 died unexpectedly: exited "
            "with exit code 3 *, and the test never took note of it in talk.launch.xml*",
            "E *allow_exit=[[]'quitter'[]]*",
            "FAILED *test_failing_anyway*",
            "E *launchkit.testing.WaitTimeout: timed out after 0.2 s waiting for a line "
            "containing 'said-bye'*",
        ]
    )
    assert "ERROR at teardown of test_failing_anyway" not in result.stdout.str()
