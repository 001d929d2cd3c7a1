"""The handle API on a well-behaved launch: finding processes, waiting, stopping."""

from __future__ import annotations

import re

import pytest

from launchkit.testing import LaunchTestError, ProcessDied, WaitTimeout, in_order


def test_waits_and_clean_stop(launch):
    handle = launch("launch/talker.launch.xml", args={"count": 2})
    talker = handle.process("talker")
    assert talker.wait_running(timeout=5) == talker.pid
    assert talker.wait_output("talker waiting", timeout=5) == "talker waiting"
    assert talker.wait_output(re.compile(r"hello \d$"), timeout=5) == "talker says hello 1"
    assert talker.wait_output(lambda line: line.endswith("2"), timeout=5).endswith("hello 2")
    assert talker.wait_output("to stderr", stream="stderr", timeout=5) == "talker to stderr"
    assert talker.stdout == ["talker says hello 1", "talker says hello 2", "talker waiting"]
    assert talker.stderr == ["talker to stderr"]
    assert talker.running and talker.returncode is None
    assert talker.label == "talker-1"
    handle.process("python3").wait_output("listener waiting", timeout=5)

    result = handle.stop()

    assert result.exit_codes == {"talker": 0, "python3": 0}  # unnamed: its executable's name
    result.assert_exit_codes({"*": 0})
    assert result.returncode == 0
    assert talker.returncode == 0
    assert handle.stop() is result  # stopping twice is harmless


def test_processes_are_found_by_name_attribute_executable_or_label(launch):
    handle = launch("launch/talker.launch.xml")
    listener = handle.process("python3")  # no name attribute: named after its executable
    listener.wait_output("listener waiting", timeout=5)
    assert listener.label == "python3-2"
    assert handle.process("python3-2").pid == listener.pid
    assert handle.process("talker-1").pid == handle.process("talker").pid


def test_an_unknown_process_says_which_exist(launch):
    handle = launch("launch/talker.launch.xml")
    handle.process("talker").wait_running(timeout=5)
    with pytest.raises(LaunchTestError, match=r"no process 'talkr' has started.*talker-1"):
        _ = handle.process("talkr").pid


def test_wait_timeout_names_what_was_awaited_and_shows_the_processes(launch):
    handle = launch("launch/talker.launch.xml")
    talker = handle.process("talker")
    talker.wait_output("talker waiting", timeout=5)
    with pytest.raises(WaitTimeout) as caught:
        talker.wait_output("a line that never comes", timeout=0.2)
    message = str(caught.value)
    assert "timed out after 0.2 s waiting for a line containing 'a line that never comes'" in (
        message
    )
    assert "from process 'talker'" in message
    assert "talker-1 (talker): running" in message
    assert "| talker says hello 3" in message
    assert "launcher: running" in message


def test_waiting_on_a_process_that_exits_without_the_line_fails_at_once(launch):
    handle = launch("launch/crash.launch.xml")
    with pytest.raises(ProcessDied, match=r"crasher-2 exited with exit code 3 .*before it came"):
        handle.process("crasher").wait_exit(timeout=5)
        handle.process("crasher").wait_output("never", timeout=60)


def test_assert_exit_codes_reports_every_mismatch(launch):
    handle = launch("launch/crash.launch.xml")
    assert handle.process("crasher").wait_exit(timeout=5) == 3
    result = handle.stop()
    with pytest.raises(AssertionError, match=r"crasher: exit code 3, expected exit code 0"):
        result.assert_exit_codes({"*": 0})
    with pytest.raises(AssertionError, match=r"names no process of the launch: sim"):
        result.assert_exit_codes({"sim": 0})
    result.assert_exit_codes({"crasher": {1, 3}})


def test_a_respawning_process_may_die_without_failing_waits(launch):
    handle = launch("launch/respawn.launch.xml")
    crashes = 0

    def third_crash(line: str) -> bool:
        nonlocal crashes
        crashes += line == "crashing"
        return crashes == 3

    crasher = handle.process("crasher")
    crasher.wait_output(third_crash, timeout=10)
    assert crasher.wait_exit(timeout=5) == 3
    assert handle.process("steady").wait_output("steady waiting", timeout=5)
    handle.stop().assert_exit_codes({"steady": 0, "crasher": 3})


def test_an_error_while_running_ends_every_wait_with_launchkits_message(launch, launch_dir):
    handle = launch("launch/timer_error.launch.xml")
    with pytest.raises(ProcessDied) as caught:
        handle.process("steady").wait_output("a line that never comes", timeout=60)
    where = launch_dir / "timer_error.launch.xml"
    error = f"{where}:7:19: error: command 'sh -c \"exit 4\"' failed with exit code 4"
    assert f"the launch failed: {error}" in str(caught.value)
    assert handle.stop().returncode == 1


def test_a_sequence_of_lines_is_awaited_in_order(launch):
    talker = launch("launch/talker.launch.xml").process("talker")
    assert talker.wait_output(in_order("hello 1", "hello 3", "waiting"), timeout=5) == (
        "talker waiting"
    )
    with pytest.raises(WaitTimeout, match=r"containing 'waiting', then a line containing 'hello'"):
        talker.wait_output(in_order("waiting", "hello"), timeout=0.2)
