"""The plugin's pure parts, fed scripted events (no processes)."""

from __future__ import annotations

import re

import pytest

from launchkit.runtime.events import node_name
from launchkit.testing import LaunchResult, in_order
from launchkit.testing._matchers import compile_matcher
from launchkit.testing._state import LaunchState, ProcessRecord
from launchkit.testing._waits import AllowedExits


def _started(label: str, pid: int, respawn: bool = False) -> dict[str, object]:
    return {
        "event": "started",
        "process": label,
        "name": label.rsplit("-", 1)[0],
        "node": None,
        "pid": pid,
        "cmd": ["x"],
        "respawn": respawn,
        "sigterm_timeout": 1.0,
        "sigkill_timeout": 2.0,
    }


def test_deaths_are_unexpected_only_outside_shutdown_and_without_respawn():
    state = LaunchState()
    for event in (
        _started("a-1", 10),
        _started("b-2", 11, respawn=True),
        _started("c-3", 12),
        _started("d-4", 13),
        {"event": "exited", "process": "a-1", "pid": 10, "returncode": 3},
        {"event": "exited", "process": "b-2", "pid": 11, "returncode": 3},
        {"event": "exited", "process": "c-3", "pid": 12, "returncode": 0},
        {"event": "shutdown", "reason": "done"},
        {"event": "exited", "process": "d-4", "pid": 13, "returncode": -2},
        {"event": "something new", "with": "fields"},
        {"event": "exited"},  # malformed: ignored
    ):
        state.apply(event)
    died = [label for label, r in state.processes.items() if r.died_unexpectedly()]
    assert died == ["a-1"]
    assert state.processes["a-1"].escalation == 3.0
    assert state.all_pids() == [10, 11, 12, 13]


def test_a_respawn_is_a_new_pid_of_the_same_process():
    state = LaunchState()
    state.apply(_started("a-1", 10, respawn=True))
    state.apply({"event": "exited", "process": "a-1", "pid": 10, "returncode": 1})
    state.apply(_started("a-1", 20, respawn=True))
    record = state.processes["a-1"]
    assert record.pids == [10, 20] and record.running and record.returncode is None


def test_matchers():
    substring, words = compile_matcher("lo w")
    assert substring("hello world") and not substring("hello") and "'lo w'" in words
    regex, words = compile_matcher(re.compile(r"^\d+ ok$"))
    assert regex("12 ok") and not regex("x12 ok") and words == r"a line matching /^\d+ ok$/"
    predicate, words = compile_matcher(str.isupper)
    assert predicate("LOUD") and words == "a line accepted by isupper"
    with pytest.raises(TypeError, match="expected a str"):
        compile_matcher(42)  # type: ignore[arg-type]


def test_node_names_come_from_the_ros_arguments():
    assert node_name(["x", "--ros-args", "-r", "__node:=drive", "-r", "a:=b"]) == "drive"
    assert node_name(["x", "--ros-args", "--remap", "__node:=drive"]) == "drive"
    assert node_name(["x", "-r", "a:=b"]) is None


def test_exit_code_expectations():
    result = LaunchResult({"sim": -2, "talker": 0, "crash": 3}, 0)
    result.assert_exit_codes({"sim": {0, -2}, "*": 0, "crash": 3})
    with pytest.raises(AssertionError) as caught:
        result.assert_exit_codes({"*": 0})
    assert "sim: signal SIGINT, expected exit code 0" in str(caught.value)
    assert "crash: exit code 3, expected exit code 0" in str(caught.value)
    assert "talker" not in str(caught.value)


def test_in_order_matches_a_sequence_with_lines_between():
    accepts, words = compile_matcher(in_order("start", re.compile(r"^ready$")))
    assert words == "a line containing 'start', then a line matching /^ready$/ (in this order)"
    assert [accepts(line) for line in ["ready", "starting", "noise", "ready"]] == [
        False,
        False,
        False,
        True,
    ]
    fresh, _ = compile_matcher(in_order("start"))  # each compilation starts over
    assert fresh("start")
    with pytest.raises(ValueError, match="at least one matcher"):
        in_order()


def test_allowed_exits_name_processes_and_codes():
    quitter = ProcessRecord("quitter-2", "quitter", None, ["sh"], False, 10.0, returncode=3)
    assert not AllowedExits(None).allows(quitter)
    assert AllowedExits(["quitter"]).allows(quitter)
    assert AllowedExits(["quitter-2"]).allows(quitter)
    assert AllowedExits({"quitter": 3}).allows(quitter)
    assert AllowedExits({"*": {1, 3}}).allows(quitter)
    assert not AllowedExits({"quitter": {0, 4}}).allows(quitter)
    assert not AllowedExits(["talker"]).allows(quitter)
    with pytest.raises(TypeError, match="not one string"):
        AllowedExits("quitter")


def test_reading_exit_codes_takes_note_of_them():
    result = LaunchResult({"quitter": 3}, 0)
    assert not result.noted
    assert result.exit_codes == {"quitter": 3}
    assert result.noted
    fresh = LaunchResult({"quitter": 3}, 0)
    fresh.assert_exit_codes({"quitter": 3})
    assert fresh.noted
