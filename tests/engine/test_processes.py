"""Process tests of the engine through the launchkit.testing plugin: output, exit codes,
escalation, respawn, output modes, timers, terminals. (Signals sent to the launcher itself and
the launcher being SIGKILLed are in test_supervision.py, which drives the launcher directly.)"""

from __future__ import annotations

from pathlib import Path

from launchkit.testing import in_order
from tests.engine.launcher import executable


def launch_file(tmp_path: Path, body: str) -> Path:
    """A launch file holding ``body``."""
    path = tmp_path / "t.launch.xml"
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


def test_output_lines_and_exit_codes(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        launch_file(
            tmp_path,
            '<executable name="first" output="screen" cmd="echo one"/>\n'
            '<executable name="second" output="screen" cmd="sh -c \'echo two; exit 3\'"/>',
        )
    )
    second = handle.process("second")
    second.wait_output("two")
    assert second.wait_exit() == 3  # noted: its death is expected
    assert handle.process("first").wait_output("one") == "one"
    assert handle.process("first").wait_exit() == 0
    handle.stop().assert_exit_codes({"first": 0, "second": 3})


def test_ignoring_sigint_is_escalated(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
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
    handle = launch(launch_file(tmp_path, body))
    handle.process("stubborn").wait_output("ready")
    handle.process("polite").wait_output("ready")
    result = handle.stop()
    result.assert_exit_codes({"stubborn": -9, "polite": -15})


def test_respawn_obeys_delay_and_max_retries(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        launch_file(
            tmp_path,
            '<executable name="flaky" output="screen" respawn="true" respawn_delay="0.1" '
            'respawn_max_retries="2" cmd="sh -c \'echo run; exit 1\'"/>\n'
            '<executable name="keeper" cmd="sleep 30"/>',
        )
    )
    flaky = handle.process("flaky")
    flaky.wait_output(in_order("run", "run", "run"))
    assert flaky.wait_exit() == 1
    result = handle.stop()
    assert result.output["flaky-1"].count("run") == 3


def test_output_modes(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        launch_file(
            tmp_path,
            '<executable name="quiet" cmd="echo to-the-log"/>\n'
            '<executable name="both" output="both" cmd="echo to-both"/>\n'
            '<executable name="own" output="own_log" cmd="sh -c \'echo out; echo err >&amp;2\'"/>',
        )
    )
    handle.process("both").wait_output("to-both")
    for name in ("quiet", "both", "own"):
        assert handle.process(name).wait_exit() == 0
    handle.stop()
    logs = {p.name: p.read_text() for p in handle.log_dir.rglob("*.log")}
    assert any("to-the-log" in text for text in logs.values()), sorted(logs)
    own = [text for name, text in logs.items() if name.startswith("own-3")]
    assert own and any("out" in text for text in own), sorted(logs)


def test_timer_starts_a_process_later_in_its_scope(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        launch_file(
            tmp_path,
            '<group><let name="word" value="scoped"/>\n'
            '<timer period="0.3"><executable name="late" output="screen" '
            'cmd="echo $(var word)"/></timer></group>',
        )
    )
    assert handle.process("late").wait_output("scoped", timeout=10) == "scoped"


def test_emulate_tty(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    probe = "import sys; print('tty' if sys.stdout.isatty() else 'pipe')"
    handle = launch(
        launch_file(
            tmp_path,
            executable("with", probe, emulate_tty="true") + "\n" + executable("without", probe),
        )
    )
    assert handle.process("with").wait_output("tty") == "tty"
    assert handle.process("without").wait_output("pipe") == "pipe"


def test_grandchildren_of_sh_are_stopped(launch, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    handle = launch(
        launch_file(
            tmp_path,
            '<executable name="sh" output="screen" '
            "cmd=\"sh -c 'sleep 300 &amp; echo grandchild $!; wait'\"/>",
        )
    )
    handle.process("sh").wait_output("grandchild")
    handle.stop()  # the plugin fails the test if the grandchild survives
