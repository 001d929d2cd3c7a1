"""Process tests that act on the launcher itself: SIGINT/SIGTERM/SIGHUP to it, a second
Ctrl-C, the launcher SIGKILLed, its exit status, its screen output and its run-time errors.
They drive ``launchkit run`` directly (tests/engine/launcher.py) because the pytest plugin
owns those signals; everything else is in test_processes.py, through the plugin.

Synchronisation is on what the launcher prints (each wait has a deadline); no sleeps.
"""

from __future__ import annotations

import os
import signal

import pytest

from tests.engine.launcher import alive, executable, wait_gone

IGNORE_SIGINT = (
    "import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); "
    "{extra}print('ready', flush=True); time.sleep(300)"
)


def test_screen_output_is_prefixed_and_in_order(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        '<executable name="first" output="screen" cmd="echo one"/>\n'
        '<executable name="second" output="screen" cmd="sh -c \'echo two; exit 3\'"/>'
    )
    assert launcher.finish() == 0
    text = launcher.text
    started = text.index("[INFO] [first-1]: process started with pid [")
    assert text.index("[first-1] one") > started
    assert "[second-2] two" in text
    assert "[ERROR] [second-2]: process has died [pid" in text and "exit code 3" in text
    assert text.index("[first-1] one") < text.index(
        "[INFO] [first-1]: process has finished cleanly"
    )


def test_all_well_exits_zero_after_timer_shutdown(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        '<executable name="sleeper" cmd="sleep 30"/>\n'
        '<timer period="0.3"><shutdown reason="enough"/></timer>'
    )
    assert launcher.finish() == 0
    assert "enough" in launcher.text
    wait_gone(list(launcher.pids.values()))


def test_executables_learn_the_router_given_with_dash_dash_router(
    run, monkeypatch: pytest.MonkeyPatch
) -> None:  # type: ignore[no-untyped-def]
    # A plain <executable> may be a ROS program (gazebo_ros's gzserver is an ExecuteProcess).
    monkeypatch.delenv("LAUNCHKIT_ROUTER", raising=False)
    endpoint = "tcp/127.0.0.1:17999"
    code = "import os; print('router', os.environ.get('LAUNCHKIT_ROUTER'), flush=True)"
    launcher = run(executable("probe", code), "--router", endpoint)
    assert launcher.wait_line("router ").endswith(f"router {endpoint}")
    assert launcher.finish() == 0


def test_missing_program_is_an_error(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run('<executable cmd="no-such-program-xyz --flag"/>')
    assert launcher.finish() != 0
    assert "no-such-program-xyz" in launcher.text


def test_failed_required_process_gives_its_exit_code(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        '<executable name="sleeper" cmd="sleep 30"/>\n'
        '<executable name="required" on_exit="shutdown" cmd="sh -c \'exit 7\'"/>'
    )
    assert launcher.finish() == 7
    wait_gone(list(launcher.pids.values()))


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_signal_stops_everything(run, signum: int) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        executable("py", "import time; print('ready', flush=True); time.sleep(300)")
        + '\n<executable name="sh" output="screen" '
        "cmd=\"sh -c 'sleep 300 &amp; echo grandchild $!; wait'\"/>"
    )
    launcher.wait_line("[py-1] ready")
    grandchild = int(launcher.wait_line("grandchild").split()[-1])
    launcher.signal(signum)
    # ros2 launch exits 0 after Ctrl-C, and dies of SIGTERM and SIGHUP (a shell sees 128 + N)
    assert launcher.finish() == (0 if signum == signal.SIGINT else 128 + signum)
    wait_gone([*launcher.pids.values(), grandchild])


def test_second_ctrl_c_escalates_at_once(run) -> None:  # type: ignore[no-untyped-def]
    stubborn = IGNORE_SIGINT.format(extra="")
    launcher = run(executable("slow", stubborn, sigterm_timeout="60", sigkill_timeout="60"))
    launcher.wait_line("[slow-1] ready")
    launcher.signal(signal.SIGINT)
    launcher.wait_line("SIGINT")
    launcher.signal(signal.SIGINT)
    waiting = launcher.wait_line("waiting for")
    assert "slow-1" in waiting
    assert launcher.finish(timeout=20) == 0
    wait_gone(list(launcher.pids.values()))


def test_launcher_killed_with_sigkill_leaves_no_orphans(run) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        executable("py", IGNORE_SIGINT.format(extra=""))
        + '\n<executable name="sh" output="screen" '
        "cmd=\"sh -c 'sleep 300 &amp; echo grandchild $!; wait'\"/>"
    )
    launcher.wait_line("[py-1] ready")
    grandchild = int(launcher.wait_line("grandchild").split()[-1])
    children = list(launcher.pids.values())
    assert all(alive(pid) for pid in [*children, grandchild])
    os.kill(launcher.proc.pid, signal.SIGKILL)
    launcher.proc.wait(10)
    wait_gone([*children, grandchild])


def test_failing_command_substitution_at_run_time_stops_everything(run, tmp_path) -> None:  # type: ignore[no-untyped-def]
    launcher = run(
        '<executable name="sleeper" cmd="sleep 300"/>'
        + '\n<timer period="0.2">\n  <log message="$(command \'false\')"/>\n</timer>'
    )
    assert launcher.finish() == 1
    assert "t.launch.xml:4:" in launcher.text and "'false' failed" in launcher.text
    assert "Traceback" not in launcher.text
    wait_gone(list(launcher.pids.values()))
