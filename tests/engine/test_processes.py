"""Process tests of the engine through the launchkit.testing plugin: output, exit codes,
escalation, respawn, output modes, timers, terminals. (Signals sent to the launcher itself and
the launcher being SIGKILLed are in test_supervision.py, which drives the launcher directly.)"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from launchkit.testing import LaunchFactory, LaunchHandle, in_order
from tests.engine.conftest import write
from tests.engine.launcher import executable

Start = Callable[[str], LaunchHandle]


@pytest.fixture
def start(launch: LaunchFactory, tmp_path: Path) -> Start:
    """Launch, through the plugin, a launch file holding ``body``."""
    return lambda body: launch(write(tmp_path, body))


def test_output_lines_and_exit_codes(start: Start) -> None:
    handle = start(
        '<executable name="first" output="screen" cmd="echo one"/>\n'
        '<executable name="second" output="screen" cmd="sh -c \'echo two; exit 3\'"/>',
    )
    second = handle.process("second")
    second.wait_output("two")
    assert second.wait_exit() == 3  # noted: its death is expected
    assert handle.process("first").wait_output("one") == "one"
    assert handle.process("first").wait_exit() == 0
    handle.stop().assert_exit_codes({"first": 0, "second": 3})


def test_ignoring_sigint_is_escalated(start: Start) -> None:
    ignore = "import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); {x}"
    body = (
        executable(
            "stubborn",
            ignore.format(
                x="signal.signal(signal.SIGTERM, signal.SIG_IGN); print('ready'); time.sleep(300)"
            ),
            sigterm_timeout="0.3",
            sigkill_timeout="0.3",
        )
        + "\n"
        + executable(
            "polite",
            ignore.format(x="print('ready'); time.sleep(300)"),
            sigterm_timeout="0.3",
        )
    )
    handle = start(body)
    handle.process("stubborn").wait_output("ready")
    handle.process("polite").wait_output("ready")
    result = handle.stop()
    result.assert_exit_codes({"stubborn": -9, "polite": -15})


def test_respawn_obeys_delay_and_max_retries(start: Start) -> None:
    handle = start(
        '<executable name="flaky" output="screen" respawn="true" respawn_delay="0.1" '
        'respawn_max_retries="2" cmd="sh -c \'echo run; exit 1\'"/>\n'
        '<executable name="keeper" cmd="sleep 30"/>',
    )
    flaky = handle.process("flaky")
    flaky.wait_output(in_order("run", "run", "run"))
    assert flaky.wait_exit() == 1
    result = handle.stop()
    assert result.output["flaky-1"].count("run") == 3


def test_output_modes(start: Start) -> None:
    handle = start(
        '<executable name="quiet" cmd="echo to-the-log"/>\n'
        '<executable name="both" output="both" cmd="echo to-both"/>\n'
        '<executable name="own" output="own_log" cmd="sh -c \'echo out; echo err >&amp;2\'"/>',
    )
    handle.process("both").wait_output("to-both")
    for name in ("quiet", "both", "own"):
        assert handle.process(name).wait_exit() == 0
    handle.stop()
    logs = {p.name: p.read_text() for p in handle.log_dir.rglob("*.log")}
    assert any("to-the-log" in text for text in logs.values()), sorted(logs)
    own = [text for name, text in logs.items() if name.startswith("own-3")]
    assert own and any("out" in text for text in own), sorted(logs)


def test_timer_starts_a_process_later_in_its_scope(start: Start) -> None:
    handle = start(
        '<group><let name="word" value="scoped"/>\n'
        '<timer period="0.3"><executable name="late" output="screen" '
        'cmd="echo $(var word)"/></timer></group>',
    )
    assert handle.process("late").wait_output("scoped", timeout=10) == "scoped"


def test_emulate_tty(start: Start) -> None:
    probe = "import sys; print('tty' if sys.stdout.isatty() else 'pipe')"
    handle = start(
        executable("with", probe, emulate_tty="true") + "\n" + executable("without", probe),
    )
    assert handle.process("with").wait_output("tty") == "tty"
    assert handle.process("without").wait_output("pipe") == "pipe"


def test_grandchildren_of_sh_are_stopped(start: Start) -> None:
    handle = start(
        '<executable name="sh" output="screen" '
        "cmd=\"sh -c 'sleep 300 &amp; echo grandchild $!; wait'\"/>",
    )
    handle.process("sh").wait_output("grandchild")
    handle.stop()  # the plugin fails the test if the grandchild survives
