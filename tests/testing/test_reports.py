"""What a failing process test shows: the wait's message, and each process's output as a
section of the report (checked on real pytest runs through pytester)."""

from __future__ import annotations

import pytest

from tests.testing.conftest import LAUNCH_DIR


@pytest.fixture
def talker_test(pytester: pytest.Pytester) -> pytest.Pytester:
    """A pytester folder whose tests can name the talker launch file."""
    pytester.makeconftest(f"TALKER = {str(LAUNCH_DIR / 'talker.launch.xml')!r}")
    return pytester


def test_a_wait_failure_says_what_was_awaited_and_shows_every_process(talker_test):
    talker_test.makepyfile(
        """
        from conftest import TALKER

        def test_never(launch):
            handle = launch(TALKER, args={"count": 25})
            handle.process("talker").wait_output("talker waiting", timeout=5)
            handle.process("talker").wait_output("the end", timeout=0.3)
        """
    )
    result = talker_test.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "E *launchkit.testing.WaitTimeout: timed out after 0.3 s waiting for "
            "a line containing 'the end' from process 'talker' in talker.launch.xml",
            "E *processes of the launch:",
            "E *  talker-1 (talker): running [[]pid *[]]",
            "E *    last lines of output (27 in all):",
            "E *    | ... 7 earlier lines ...",
            "E *    | talker says hello 8",
            "E *  python3-2 (python3): *",
            "E *  launcher: running; log *launcher.log",
            # the report sections: every line of every process, and the launcher's
            "*- launchkit talker.launch.xml: talker-1 -*",
            "running [[]pid *[]]; cmd: *worker.py talk talker 25",
            "[[]stdout[]] talker says hello 1",
            "*- launchkit talker.launch.xml: python3-2 -*",
            "*- launchkit talker.launch.xml: launcher -*",
            "[[]INFO[]] [[]talker-1[]]: process started with pid *",
        ]
    )


def test_a_passing_test_has_no_process_sections(talker_test):
    talker_test.makepyfile(
        """
        from conftest import TALKER

        def test_fine(launch):
            launch(TALKER).process("talker").wait_output("talker waiting", timeout=5)
        """
    )
    result = talker_test.runpytest("-p", "no:cacheprovider", "-rA")
    result.assert_outcomes(passed=1)
    assert "launchkit talker.launch.xml" not in result.stdout.str()


def test_a_module_launch_is_shared_and_stopped_after_the_module(talker_test):
    talker_test.makepyfile(
        """
        import pytest
        from conftest import TALKER

        PIDS = []

        @pytest.fixture(scope="module")
        def talker(launch_module):
            return launch_module(TALKER)

        def test_first(talker):
            PIDS.append(talker.process("talker").wait_running(timeout=5))

        def test_second(talker):
            PIDS.append(talker.process("talker").wait_running(timeout=5))
            assert PIDS[0] == PIDS[1]
            assert not talker.stopped

        def test_third_fails(talker):
            talker.process("talker").wait_output("never", timeout=0.1)
        """
    )
    result = talker_test.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(passed=2, failed=1)
    result.stdout.fnmatch_lines(["*- launchkit talker.launch.xml: talker-1 -*"])


def test_a_bad_timeout_scale_stops_the_run_before_any_test(pytester, monkeypatch):
    pytester.makepyfile("def test_nothing():\n    pass\n")
    monkeypatch.setenv("LAUNCHKIT_TIMEOUT_SCALE", "0")
    result = pytester.runpytest("-p", "no:cacheprovider")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(["*LAUNCHKIT_TIMEOUT_SCALE='0': expected a positive number*"])
